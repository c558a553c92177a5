#include "gpu/transition/transition_params.h"

#include <algorithm>
#include <cstring>

namespace animorph::gpu {

void packTransitionParams(const TransitionFrame& f, TransitionParams& out) {
  std::memset(&out, 0, sizeof(out));
  uint32_t flags = 0;
  if (f.perVertex) flags |= AM_TR_PER_VERTEX;
  if (f.expand) flags |= AM_TR_EXPAND;
  const bool fits = f.primitives.size() <= kTransitionMaxSegments && f.segments.size() <= kTransitionMaxSegments;
  if (f.reproject && fits) flags |= AM_TR_REPROJECT;
  if (f.capsules) flags |= AM_TR_CAPSULES;
  if (f.combineMax) flags |= AM_TR_COMBINE_MAX;
  out.alphaParams = glm::vec4(f.uniformAlpha, f.progress, f.shift, f.duration);
  out.reprojParams = glm::vec4(f.reprojectFrom, f.tolerance, f.maxStep, f.threshold);
  const uint32_t prims = fits ? uint32_t(f.primitives.size()) : 0u;
  const uint32_t segs = fits ? uint32_t(f.segments.size()) : 0u;
  out.mode = glm::uvec4(flags, prims, segs, uint32_t(std::max(0, f.maxIterations)));
  const size_t lutCount = std::min<size_t>(f.easingTable.size(), AM_TRANSITION_LUT_FLOATS);
  for (size_t k = 0; k < lutCount; ++k) out.lut[k / 4][int(k % 4)] = f.easingTable[k];
  for (uint32_t i = 0; i < prims; ++i) {
    out.prims[3 * i] = f.primitives[i].r0;
    out.prims[3 * i + 1] = f.primitives[i].r1;
    out.prims[3 * i + 2] = f.primitives[i].r2;
  }
  for (uint32_t i = 0; i < segs; ++i) {
    out.segs[2 * i] = glm::vec4(f.segments[i].a, f.segments[i].radius);
    out.segs[2 * i + 1] = glm::vec4(f.segments[i].b, 0.0f);
  }
}

}  // namespace animorph::gpu
