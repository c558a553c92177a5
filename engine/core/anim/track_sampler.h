#pragma once
// A Track<T> precompiled for evaluation at many times: each key segment's
// Hermite coefficients (derivatives included) computed once, a constant track
// reduced to its value, and a cursor on the last segment used (scrubbing and
// playback move little, so most calls search nothing). sample(t) returns
// exactly Track::evaluate(t), bit for bit: the same float operations in the
// same order (anim/track_segment.h). Driven tracks call the track's driver.
// The sampler copies what it needs, except for a driven track, which must
// outlive it. Edits to the track after construction are not seen (rebuild it).
// Not thread-safe across concurrent calls (the cursor): one thread at a time.
#include <cstdint>
#include <vector>

#include "core/anim/track.h"

namespace animorph {

template <class T>
class TrackSampler {
 public:
  TrackSampler() = default;  // a constant: T's zero / identity
  explicit TrackSampler(const Track<T>& track);

  T sample(double timeSec) const;
  bool constant() const { return times_.size() <= 1 && !driven_; }

 private:
  struct Segment {
    double dt = 0.0;                      // k1.timeSec - k0.timeSec
    float h = 0.0f;                       // float(dt)
    KeyInterp interp = KeyInterp::Hermite;
    T c[6]{};                             // Hermite: coefficients; Linear: c[0] = p0, c[1] = p1 - p0
  };
  T segmentValue(size_t i, double timeSec) const;

  const Track<T>* driven_ = nullptr;
  std::vector<double> times_;     // key times
  std::vector<T> values_;         // key values (quaternion segments slerp between them)
  std::vector<Segment> segments_;  // segment i: key i to key i + 1
  int degree_ = 2;
  T constant_{};
  mutable size_t cursor_ = 0;     // the segment of the last call inside the key range
};

extern template class TrackSampler<float>;
extern template class TrackSampler<glm::vec3>;
extern template class TrackSampler<glm::quat>;

}  // namespace animorph
