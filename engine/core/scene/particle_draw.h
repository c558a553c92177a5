#pragma once
// A BlobTree draw's particles (docs/particles.md): the point primitives its tree reaches through
// operators only (particles/particle_tree.h: a converted or simulated shape, the statue demo's
// C(t); not a creature whose points are templates of meta-primitives under its joints' frames),
// each at its centre with its visible radius. The renderer draws a ParticleDraw as spheres
// (gpu/render/particle_spheres.h); when the editor's viewport shows a draw as its particles rather
// than its surface is the editor's policy (editor/particle_view.h).
//
// Particles spread far apart are lost by a polygonised surface: the grid (resolution cells along
// the longest side of the particles' bounds) gets cells larger than the particles, and its corners
// miss them (the statue at 200 J spreads over 47 m: 0.37 m cells for 2 cm particles, and the
// surface shows nothing). particlesBelowGrid says when.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/project/project.h"
#include "core/particles/particle_tree.h"
#include "core/scene/scene_frame.h"

namespace animorph {

// One draw's particles at its time, in the tree's space (model maps them to the world).
struct ParticleDraw {
  std::string actorId;
  glm::mat4 model{1.0f};
  std::vector<glm::vec3> centres;
  std::vector<float> radii;  // visible radius of each (where a point alone reaches the threshold)
  // The colour of each (its point's colour track at the draw's time, sRGB: a converted shape's
  // particles keep the colour of the surface point they came from); empty: the draw's colour.
  std::vector<glm::vec3> colors;
};

// The draw's tree (its own, else its BlobTree actor's in project) when it has at least minParticles
// particles; null otherwise (no tree, or fewer particles). The animorphosis' C(t) snapshot stays
// alive in its cache until the next frame's.
const BlobTree* particleTree(const BlobDraw& draw, const Project& project, size_t minParticles);

// The particles of a draw's tree (its own, else the actor's) at its time, with their colours; empty
// when the tree has fewer than minParticles particles.
ParticleDraw particleDraw(const BlobDraw& draw, const Project& project, size_t minParticles);

// Whether a grid of resolution cells along the longest side of the particles' bounds (centres
// grown by their radii) has cells more than twice the particles' median visible radius: most of
// them would fall between its corners. False when that median is 0 (points that show only
// together, e.g. a creature's blend, are not separate particles). cellSize (if given) gets the cell, in the tree's space.
bool particlesBelowGrid(const ParticleDraw& draw, int resolution, float* cellSize = nullptr,
                        float* medianRadius = nullptr);

}  // namespace animorph
