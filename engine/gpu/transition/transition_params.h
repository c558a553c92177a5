#pragma once
// The per-draw parameter block of the GPU transition (std430 mirror of
// TransitionParams in shaders/include/transition.glsl), packed from the
// CPU-side TransitionFrame (engine/core/scene/transition_frame.h).
#include <glm/glm.hpp>

#include "core/scene/transition_frame.h"
#include "transition_constants.h"

namespace animorph::gpu {

struct TransitionParams {
  glm::vec4 alphaParams;   // uniform alpha, progress, shift, duration
  glm::vec4 reprojParams;  // reprojectFrom, tolerance, longest step (m), threshold
  glm::uvec4 mode;         // AM_TR_* flags, primitives, segments, Newton iterations
  glm::vec4 reserved;
  glm::vec4 lut[AM_TRANSITION_LUT_VEC4];
  glm::vec4 prims[3 * AM_TRANSITION_MAX_SEGMENTS];
  glm::vec4 segs[2 * AM_TRANSITION_MAX_SEGMENTS];
};
static_assert(sizeof(TransitionParams) == (4 + AM_TRANSITION_LUT_VEC4 + 5 * AM_TRANSITION_MAX_SEGMENTS) * 16);
static_assert(kTransitionMaxSegments == AM_TRANSITION_MAX_SEGMENTS);
static_assert(kTransitionEasingIntervals + 1 == AM_TRANSITION_LUT_FLOATS);

// Packs f. More primitives or segments than the block holds turn re-projection
// off (transitionFrame never produces that).
void packTransitionParams(const TransitionFrame& f, TransitionParams& out);

}  // namespace animorph::gpu
