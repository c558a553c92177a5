#pragma once
// Collapse onto / expansion from the stand-in (docs/design.md §4, paper 1 §3.2):
//   p'_i(t) = sum_j w_ij M_j(t) lerp(p_i, p_i + dp_i, alpha_i(t))
//   n'_i(t) = normalize(M_i(t)^-T nlerp(n_i, n~_i, alpha_i(t)))
// with dp_i and n~_i from projecting the vertex onto the stand-in once, in the
// mesh's bind space. Skinning drift (the blended vertex moves differently from
// the rigid segments) is removed near alpha = 1 by re-projecting onto the
// posed stand-in, so alpha = 1 lies on that frame's implicit surface.
// Colour follows the position: c_i(t) = lerp(c_i, c~_i, alpha_i(t)), from the
// vertex's textured colour c_i to the stand-in's colour c~_i at the point it
// lands on (docs/morph.md, "Colour through the morph").
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/anim/track.h"
#include "core/field/field_program.h"
#include "core/rig/character.h"
#include "core/standin/project_onto_standin.h"
#include "core/standin/standin.h"

namespace animorph {

// A character's vertices bound to its stand-in (concatenated over meshNodes()).
struct StandinBinding {
  std::vector<glm::vec3> offsets;         // dp_i, bind mesh space
  std::vector<glm::vec3> standinNormals;  // n~_i, bind mesh space, unit
  ProjectionStats stats;
  // Colour; all three empty when the character has no colour of its own (rig/vertex_colors.h).
  std::vector<glm::vec4> vertexColors;      // c_i: the vertex's textured colour, linear RGBA
  std::vector<glm::vec4> standinColors;     // c~_i: the stand-in's colour where the vertex lands, linear
  std::vector<SegmentColors> segmentColors;  // per stand-in segment (standin/standin_colors.h)
  bool hasColors() const { return !vertexColors.empty() && vertexColors.size() == standinColors.size(); }
};

// Each vertex's colour at alpha (one per vertex; lerp(c_i, c~_i, alpha_i)) into out; out is
// cleared when the binding has no colours or alpha has another length.
void transitionColors(const StandinBinding& binding, const std::vector<float>& alpha, std::vector<glm::vec4>& out);

// Projects every vertex of c, posed at clipTimeSec of clip (null: rest pose),
// blend shapes included, onto the stand-in posed the same way, and expresses
// the moves in bind space, from the unmorphed bind shape (offsets reach the
// stand-in whatever the blend shapes do later).
StandinBinding bindToStandin(const Character& c, const Standin& s, const AnimationClip* clip, float clipTimeSec,
                             const ProjectionSettings& settings);

struct TransitionSettings {
  // Vertices with alpha above this are pulled onto the posed field, fully at
  // alpha = 1 (smoothstep in between). 1 disables re-projection.
  float reprojectFrom = 0.75f;
  ProjectionSettings reprojection{12, 1e-5f, 0.5f, 0};
  int threads = 0;  // 0: all hardware threads
  // Blend-shape weights of each mesh node (meshNodes() order; rig/pose.h
  // morphWeightsAt); empty, or an empty entry: the mesh's bind shape. The
  // morphed mesh is what alpha = 0 shows; it fades into the stand-in binding
  // as alpha grows (the binding's offsets are from the unmorphed bind shape).
  std::vector<std::vector<float>> morphWeights;
};

struct TransitionStats {
  size_t reprojected = 0;          // vertices pulled onto the posed field
  size_t reprojectFailures = 0;    // of those, not converged
  double milliseconds = 0.0;
};

// The per-vertex alpha of a transition at progress u in [0, 1] (u = 0 at the
// transition's start): alpha = easing(local u). Without a weight map every
// vertex uses the whole transition; with one, vertex i starts at
// shift * (1 - m_i) and lasts 1 - shift, so painted vertices (m = 1) move
// first and every vertex reaches its end at u = 1. expand: alpha = 1 - that
// (the target's expansion, painted vertices again first).
// Intervals of the easing table transitionAlphas reads with a weight map.
inline constexpr int kTransitionEasingIntervals = 512;

// The easing sampled at kTransitionEasingIntervals + 1 evenly spaced u in
// [0, 1], clamped to [0, 1], with exact ends (0 and 1): the table that
// transitionAlphas interpolates per vertex (and the GPU transition reads).
void transitionEasingTable(const FloatTrack& easing, std::vector<float>& table);

void transitionAlphas(double u, const FloatTrack& easing, const std::vector<float>& weightMap, float shift, bool expand,
                      size_t vertexCount, std::vector<float>& alpha);

// Evaluates the transition of c at pose globals (rig/pose.h) under root (the
// actor transform): world positions and unit normals of every vertex,
// concatenated over meshNodes(). alpha has one entry per vertex. posedField
// and posedSegments (the stand-in posed at the same time, world space) are
// needed for re-projection; pass null to skip it.
TransitionStats evaluateTransition(const Character& c, const StandinBinding& binding,
                                   const std::vector<glm::mat4>& globals, const glm::mat4& root,
                                   const std::vector<float>& alpha, const FieldProgram* posedField,
                                   const std::vector<PosedSegment>* posedSegments, const TransitionSettings& settings,
                                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

// The default easing of transitions: smoothstep 3u^2 - 2u^3 (Hermite, flat ends).
FloatTrack smoothstepTrack();

}  // namespace animorph
