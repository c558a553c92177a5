#pragma once
// Particles as BlobTree primitives (docs/particles.md): every point primitive of a
// tree reached from its root through operators only is one particle (its centre the
// position, its visible radius the collision radius). A point under a space map (a
// frame, a warp) or a meta-primitive (a template repeated along a spline or over a
// patch) is not one: its centre is not a place in the tree's space. simulateTreeParticles runs the particle system from their positions at
// a time and bakes the trajectories into their centre tracks (particles/
// trajectory_bake.h), so the result saves, undoes and plays like any animated
// BlobTree; the other nodes are left as they are.
#include <vector>

#include "core/blobtree/blob_tree.h"
#include "core/particles/particle_system.h"
#include "core/particles/trajectory_bake.h"

namespace animorph {

// Calls fn(node) for each particle node (BlobNode or const BlobNode), depth first.
template <class Node, class Fn>
void forEachParticleNode(Node& n, Fn&& fn) {
  if (n.type == NodeType::Point) fn(n);
  else if (isOperatorType(n.type))
    for (Node& c : n.children) forEachParticleNode(c, fn);
}

// The particles of a tree, in depth-first order, at time t.
struct TreeParticles {
  std::vector<int> nodeIds;
  ParticleSet set;  // positions at t, radii = visible radius of each point alone; masses empty (equal)
};
TreeParticles treeParticles(const BlobTree& tree, double timeSec);

// Distance from a point primitive's centre at which I (1 - (d/R)^2)^k = T (0 if I <= T).
float visiblePointRadius(float radius, float intensity, float stiffness, float threshold);

struct ParticleBakeOptions {
  double startSec = 0.0;    // the simulation's step 0 sits at this time of the tree's timeline
  float tolerance = 2e-3f;  // m: largest distance between a baked track and the simulation at any step
  bool reverse = false;     // write the animation backwards (the last step at startSec)
  double quantum = 0.0;     // > 0: key values rounded to it (trajectory_bake.h), for shorter files
};

struct ParticleBakeReport {
  size_t particles = 0;
  int steps = 0;
  size_t keys = 0;          // keys written in all
  float maxError = 0.0f;    // largest track-to-simulation distance at the steps
  ImpulseReport impulse;
  bool cancelled = false;
};

// Simulates the tree's particles (from their positions at options.startSec, or at
// the end of the simulation's duration when reverse) and replaces their centre
// tracks with the baked trajectories. Errors: no point primitive, bad settings.
// When cancelled the tree is unchanged and report.cancelled is true.
Result<ParticleBakeReport> simulateTreeParticles(BlobTree& tree, const ParticleSettings& settings,
                                                 const ParticleBakeOptions& options);

}  // namespace animorph
