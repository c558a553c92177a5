#pragma once
// The parameters of the generic tree C's nodes precompiled for sampling at
// many times (GenericProgramCompiler builds one per C): every animated track
// as a TrackSampler (anim/track_sampler.h: segment coefficients computed once,
// a cursor on the last segment), every constant one as its value. The values
// and blends are those of param_blend.h bit for bit: the same float operations
// in the same order. One side (A or B) of a node is a run of slots, one per
// parameter; a node's slots are sampled by one thread at a time.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/anim/track_sampler.h"
#include "core/animorphosis/param_blend.h"
#include "core/blobtree/blob_tree.h"

namespace animorph {

class ParamSamplers {
 public:
  // Slots for n's parameters; returns the first one's index. blendCounts[k] (when given): the
  // number of points parameter k's list is resampled to when blended with the other side's.
  uint32_t add(const BlobNode& n, const std::vector<size_t>* blendCounts = nullptr);
  // A slot for the q of a bridged blend / union / hyper-blend (bridgeQ's value is max(1, slot)).
  uint32_t addBridgeQ(const BlobNode& n);

  // A parameter slot into a value slot of the compiler: a float in x, a vector in xyz, a
  // quaternion as x, y, z, w (a list goes to `list`).
  void constant(uint32_t slot, double t, glm::vec4& out, std::vector<glm::vec3>& list) const;
  void blend(uint32_t a, uint32_t b, double tA, double tB, float s, glm::vec4& out,
             std::vector<glm::vec3>& list) const;
  float floatAt(uint32_t slot, double t) const;
  // blendFloat of two float slots.
  float blendFloatAt(uint32_t a, uint32_t b, double tA, double tB, float s) const {
    return (1.0f - s) * floatAt(a, tA) + s * floatAt(b, tB);
  }
  float bridgeQ(uint32_t slot, double t) const { return std::max(1.0f, floatAt(slot, t)); }
  // Whether any of slots [first, first + count) moves with time (an animated track, a point list with
  // an animated point): false means their values at every time are those at time 0.
  bool animated(uint32_t first, uint32_t count) const;

 private:
  struct Slot {
    ParamKind kind = ParamKind::Float;
    bool animated = false;
    uint32_t index = 0;  // animated: into the kind's samplers; lists: into lists_; else: into constants_
  };
  struct PointList {
    uint32_t first = 0, count = 0;        // samplers in points_
    std::vector<ResampleWeight> toBlend;  // to the blended count (empty: no resampling)
    // Every point constant: the list's values, as sampled and as resampled (toBlend), kept once
    // in fixedValues_ from these offsets (-1: not constant).
    int32_t fixedAt = -1, fixedResampledAt = -1;
  };
  glm::vec3 vec3At(const Slot& s, double t) const;
  glm::quat quatAt(const Slot& s, double t) const;
  // The points (n of them) in out, or in fixedValues_ when constant.
  const glm::vec3* pointsAt(const PointList& p, double t, bool resample, std::vector<glm::vec3>& out,
                            size_t& n) const;
  static void resampled(const PointList& p, const glm::vec3* at, std::vector<glm::vec3>& out);

  std::vector<Slot> slots_;
  std::vector<glm::vec4> constants_;
  std::vector<TrackSampler<float>> floats_;
  std::vector<TrackSampler<glm::vec3>> vec3s_;
  std::vector<TrackSampler<glm::quat>> quats_;
  std::vector<TrackSampler<glm::vec3>> points_;
  std::vector<PointList> lists_;
  std::vector<glm::vec3> fixedValues_;  // constant lists' values, in the order the lists were added
};

}  // namespace animorph
