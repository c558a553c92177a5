#include "core/anim/track.h"

#include <algorithm>
#include <cmath>

#include "core/anim/track_segment.h"

namespace animorph {

namespace {

// Per-type helpers so one implementation serves float and vec3 (linear spaces).
template <class T>
T zeroOf() {
  if constexpr (std::is_same_v<T, glm::quat>) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  else return T(0.0f);
}

// log(a^-1 b) as a pure quaternion (0, axis * halfAngle), shortest arc.
glm::vec3 relativeLog(const glm::quat& a, const glm::quat& bIn) {
  glm::quat d = glm::conjugate(a) * shortArc(a, bIn);
  glm::vec3 v(d.x, d.y, d.z);
  float sn = glm::length(v);
  if (sn < 1e-12f) return glm::vec3(0.0f);
  float half = std::atan2(sn, d.w);
  return v * (half / sn);
}

}  // namespace

template <class T>
Track<T>::Track() {
  keys_.push_back(TrackKey<T>{0.0, zeroOf<T>()});
}

template <class T>
Track<T>::Track(const T& constant) {
  keys_.push_back(TrackKey<T>{0.0, constant});
}

template <class T>
void Track<T>::setKey(const TrackKey<T>& key) {
  auto it = std::lower_bound(keys_.begin(), keys_.end(), key.timeSec,
                             [](const TrackKey<T>& k, double t) { return k.timeSec < t; });
  if (it != keys_.end() && it->timeSec == key.timeSec) *it = key;
  else keys_.insert(it, key);
}

template <class T>
void Track<T>::setKey(double timeSec, const T& value, KeyInterp interp) {
  TrackKey<T> k;
  k.timeSec = timeSec;
  k.value = value;
  k.interp = interp;
  setKey(k);
}

template <class T>
void Track<T>::keyDerivatives(size_t i, T& d1, T& d2) const {
  if constexpr (std::is_same_v<T, glm::quat>) {
    d1 = d2 = glm::quat(0.0f, 0.0f, 0.0f, 0.0f);
    (void)i;
  } else {
    const auto& k = keys_[i];
    if (k.userDerivatives) {
      d1 = k.d1;
      d2 = k.d2;
      return;
    }
    catmullRomDerivatives(keys_, i, d1, d2);
  }
}

FloatTrack hermiteRampTrack(float slope0, float slope1) {
  FloatTrack t;
  t.clearKeys();
  for (int k = 0; k < 2; ++k) {
    TrackKey<float> key;
    key.timeSec = k;
    key.value = float(k);
    key.interp = KeyInterp::Hermite;
    key.userDerivatives = true;
    key.d1 = k == 0 ? slope0 : slope1;
    t.setKey(key);
  }
  return t;
}

template <class T>
T Track<T>::evaluate(double t) const {
  if (driver_) return driver_(t);
  if (keys_.empty()) return zeroOf<T>();
  if (keys_.size() == 1 || t <= keys_.front().timeSec) return keys_.front().value;
  if (t >= keys_.back().timeSec) return keys_.back().value;
  size_t i = size_t(std::upper_bound(keys_.begin(), keys_.end(), t,
                                     [](double tt, const TrackKey<T>& k) { return tt < k.timeSec; }) -
                    keys_.begin()) - 1;
  const auto& k0 = keys_[i];
  const auto& k1 = keys_[i + 1];
  float h = float(k1.timeSec - k0.timeSec);
  float s = float((t - k0.timeSec) / (k1.timeSec - k0.timeSec));
  if (k0.interp == KeyInterp::Constant) return k0.value;
  if constexpr (std::is_same_v<T, glm::quat>) {
    return slerpShort(k0.value, k1.value, s);
  } else {
    if (k0.interp == KeyInterp::Linear) return k0.value + (k1.value - k0.value) * s;
    T v0, a0, v1, a1;
    keyDerivatives(i, v0, a0);
    keyDerivatives(i + 1, v1, a1);
    T c[6];
    hermiteCoefficients(k0.value, k1.value, v0, a0, v1, a1, h, degree_, c);
    return hermiteValue(c, degree_, s);
  }
}

template <class T>
T Track<T>::derivative(double t, int order) const {
  T zero;
  if constexpr (std::is_same_v<T, glm::quat>) zero = glm::quat(0.0f, 0.0f, 0.0f, 0.0f);
  else zero = T(0.0f);
  if (driver_) {
    const double h = 1e-3;
    if constexpr (std::is_same_v<T, glm::quat>) {
      glm::quat a = evaluate(t - h), b = evaluate(t), c = evaluate(t + h);
      c = shortArc(b, c);
      a = shortArc(b, a);
      if (order == 1) return (c - a) * float(0.5 / h);
      return (c - b * 2.0f + a) * float(1.0 / (h * h));
    } else {
      if (order == 1) return (evaluate(t + h) - evaluate(t - h)) / float(2.0 * h);
      return (evaluate(t + h) - evaluate(t) * 2.0f + evaluate(t - h)) / float(h * h);
    }
  }
  if (keys_.size() < 2 || t < keys_.front().timeSec || t >= keys_.back().timeSec) return zero;
  size_t i = size_t(std::upper_bound(keys_.begin(), keys_.end(), t,
                                     [](double tt, const TrackKey<T>& k) { return tt < k.timeSec; }) -
                    keys_.begin()) - 1;
  const auto& k0 = keys_[i];
  const auto& k1 = keys_[i + 1];
  float h = float(k1.timeSec - k0.timeSec);
  float s = float((t - k0.timeSec) / (k1.timeSec - k0.timeSec));
  if (k0.interp == KeyInterp::Constant) return zero;
  if constexpr (std::is_same_v<T, glm::quat>) {
    glm::vec3 v = relativeLog(k0.value, k1.value) / h;
    glm::quat w(0.0f, v.x, v.y, v.z);
    glm::quat q = slerpShort(k0.value, k1.value, s);
    return order == 1 ? q * w : q * w * w;
  } else {
    if (k0.interp == KeyInterp::Linear) return order == 1 ? (k1.value - k0.value) / h : zero;
    T v0, a0, v1, a1;
    keyDerivatives(i, v0, a0);
    keyDerivatives(i + 1, v1, a1);
    T c[6];
    int deg = degree_ == 2 ? 3 : 5;
    float h2 = h * h;
    hermiteCoefficients(k0.value, k1.value, v0, a0, v1, a1, h, degree_, c);
    T r = zero;
    if (order == 1) {
      for (int k = deg; k >= 1; --k) r = r * s + c[k] * float(k);
      return r / h;
    }
    for (int k = deg; k >= 2; --k) r = r * s + c[k] * float(k * (k - 1));
    return r / h2;
  }
}

template class Track<float>;
template class Track<glm::vec3>;
template class Track<glm::quat>;

}  // namespace animorph
