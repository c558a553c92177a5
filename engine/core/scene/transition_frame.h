#pragma once
// What the GPU transition (shaders/include/transition.glsl) needs per frame,
// computed on the CPU from the same functions the CPU transition uses: the
// alpha rule (one alpha for every vertex, or the easing table and the
// weight-map shift), and the posed stand-in field for re-projection near
// alpha = 1 (its primitives as the FieldProgram holds them, the posed segments
// for the fallback direction, the Newton settings). Per vertex data (dp_i,
// n~_i, m_i) is uploaded once per prepared morph; this is the small part that
// changes every frame.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/morph_runtime.h"

namespace animorph {

// Most stand-in segments the GPU transition re-projects onto (a stand-in with
// more is drawn without re-projection; transitionFrame reports it).
inline constexpr size_t kTransitionMaxSegments = 64;

// One stand-in primitive of the posed field, three vec4 as the shader reads them.
// Convolution: (b, length), (unit direction, weight), (S, cut radius^2, 0, 0).
// Capsule (skeletal segment): (p0, radius of influence), (p1, intensity), (stiffness, 0, 0, 0).
struct TransitionPrimitive {
  glm::vec4 r0{0.0f}, r1{0.0f}, r2{0.0f};
};

struct TransitionFrame {
  // Alpha: without a weight map every vertex has uniformAlpha (already
  // inverted for an expansion); with one, vertex i reads the table at
  // clamp((progress - shift (1 - m_i)) / duration, 0, 1).
  bool perVertex = false;
  bool expand = false;
  float uniformAlpha = 0.0f;
  float progress = 0.0f;  // u clamped to [0, 1]
  float shift = 0.0f;     // min(weight-map shift, 0.999)
  float duration = 1.0f;  // 1 - shift
  std::vector<float> easingTable;  // transitionEasingTable (perVertex only)

  // Re-projection (reproject false: none). Vertices with alpha > reprojectFrom
  // take Newton steps on f = sum - threshold, blended in by smoothstep.
  bool reproject = false;
  float reprojectFrom = 0.75f;
  int maxIterations = 12;
  float tolerance = 1e-5f;
  float maxStep = 0.0f;  // metres: maxStepRadii * median segment radius
  float threshold = 1.0f;
  bool capsules = false;    // primitives are capsules (skeletal segments), else convolution segments
  bool combineMax = false;  // capsule union: max instead of sum
  std::vector<TransitionPrimitive> primitives;
  std::vector<PosedSegment> segments;  // world space: the fallback's closest capsule surface
  std::string note;  // why re-projection is off although asked for (too many segments)
};

// The GPU transition inputs of actor a (the runtime's source when !expand, the
// target when expand) at scene time timeSec and stage progress u, with the
// runtime's easing, weight map, shift and re-projection settings; reproject
// false skips re-projection (as MorphFrameSettings::reproject does).
TransitionFrame transitionFrame(const MorphRuntime& rt, bool expand, double timeSec, double u, bool reproject);

}  // namespace animorph
