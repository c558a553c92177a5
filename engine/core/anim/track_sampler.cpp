#include "core/anim/track_sampler.h"

#include <algorithm>
#include <type_traits>

#include "core/anim/track_segment.h"

namespace animorph {

template <class T>
TrackSampler<T>::TrackSampler(const Track<T>& track) {
  if (track.driven()) {
    driven_ = &track;
    return;
  }
  const auto& keys = track.keys();
  constant_ = track.evaluate(0.0);  // no keys: T's zero / identity; one key: its value
  if (keys.size() <= 1) return;
  degree_ = track.degree();
  times_.reserve(keys.size());
  values_.reserve(keys.size());
  for (const auto& k : keys) {
    times_.push_back(k.timeSec);
    values_.push_back(k.value);
  }
  // Derivatives of each key, as Track::keyDerivatives gives them (quaternions have none).
  std::vector<T> d1(keys.size()), d2(keys.size());
  if constexpr (!std::is_same_v<T, glm::quat>) {
    for (size_t i = 0; i < keys.size(); ++i) {
      if (keys[i].userDerivatives) {
        d1[i] = keys[i].d1;
        d2[i] = keys[i].d2;
      } else {
        catmullRomDerivatives(keys, i, d1[i], d2[i]);
      }
    }
  }
  segments_.resize(keys.size() - 1);
  for (size_t i = 0; i + 1 < keys.size(); ++i) {
    const auto& k0 = keys[i];
    const auto& k1 = keys[i + 1];
    Segment& g = segments_[i];
    g.dt = k1.timeSec - k0.timeSec;
    g.h = float(g.dt);
    g.interp = k0.interp;
    if constexpr (!std::is_same_v<T, glm::quat>) {
      if (g.interp == KeyInterp::Linear) {
        g.c[0] = k0.value;
        g.c[1] = k1.value - k0.value;
      } else if (g.interp == KeyInterp::Hermite) {
        hermiteCoefficients(k0.value, k1.value, d1[i], d2[i], d1[i + 1], d2[i + 1], g.h, degree_, g.c);
      }
    }
  }
}

template <class T>
T TrackSampler<T>::segmentValue(size_t i, double t) const {
  const Segment& g = segments_[i];
  const float s = float((t - times_[i]) / g.dt);
  if (g.interp == KeyInterp::Constant) return values_[i];
  if constexpr (std::is_same_v<T, glm::quat>) {
    return slerpShort(values_[i], values_[i + 1], s);
  } else {
    if (g.interp == KeyInterp::Linear) return g.c[0] + g.c[1] * s;
    return hermiteValue(g.c, degree_, s);
  }
}

template <class T>
T TrackSampler<T>::sample(double t) const {
  if (driven_) return driven_->evaluate(t);
  if (times_.size() <= 1) return constant_;
  if (t <= times_.front()) return values_.front();
  if (t >= times_.back()) return values_.back();
  // The segment i with times_[i] <= t < times_[i + 1] (Track::evaluate's upper_bound - 1).
  size_t i = cursor_;
  if (!(times_[i] <= t && t < times_[i + 1])) {
    if (i + 2 < times_.size() && times_[i + 1] <= t && t < times_[i + 2]) ++i;
    else i = size_t(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
    cursor_ = i;
  }
  return segmentValue(i, t);
}

template class TrackSampler<float>;
template class TrackSampler<glm::vec3>;
template class TrackSampler<glm::quat>;

}  // namespace animorph
