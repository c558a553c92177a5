#pragma once
// Evolution functions: key-framed animatable parameters (docs/design.md §2, §3).
// A Track<T> maps time (seconds) to a value of T = float, glm::vec3 or glm::quat.
// Keys carry a value and, for Hermite-Ferguson interpolation of degree n, the
// first n-1 derivatives (n = 2: cubic with velocity, n = 3: quintic with
// velocity and acceleration). Derivatives are automatic (Catmull-Rom finite
// differences) unless the key sets them. Quaternion tracks slerp along the
// shortest arc (Hermite keys on quaternions also slerp). A track may instead
// be driven by a callback; a constant parameter is a track with one key.
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/util/result.h"

namespace animorph {

enum class KeyInterp { Constant, Linear, Hermite };

template <class T>
struct TrackKey {
  double timeSec = 0.0;
  T value{};
  KeyInterp interp = KeyInterp::Hermite;  // interpolation of the segment that starts at this key
  bool userDerivatives = false;            // true: d1 (and d2 for degree 3) are used as given
  T d1{};                                  // first derivative (per second)
  T d2{};                                  // second derivative (degree-3 tracks only)
  bool operator==(const TrackKey&) const = default;
};

template <class T>
class Track {
 public:
  using Driver = std::function<T(double timeSec)>;

  Track();                       // one key holding T's zero / identity
  explicit Track(const T& constant);
  static Track constant(const T& v) { return Track(v); }

  // Adds (or replaces, at an equal time) a key; keeps keys sorted by time.
  void setKey(const TrackKey<T>& key);
  void setKey(double timeSec, const T& value, KeyInterp interp = KeyInterp::Hermite);
  void clearKeys() { keys_.clear(); }
  const std::vector<TrackKey<T>>& keys() const { return keys_; }
  std::vector<TrackKey<T>>& keys() { return keys_; }

  // Hermite degree: 2 (cubic, default) or 3 (quintic). Other values are clamped.
  void setDegree(int n) { degree_ = n < 3 ? 2 : 3; }
  int degree() const { return degree_; }

  // Replaces key interpolation with a callback (not serialised); an empty function removes it.
  void setDriver(Driver d) { driver_ = std::move(d); }
  bool driven() const { return static_cast<bool>(driver_); }

  bool isConstant() const { return !driver_ && keys_.size() <= 1; }
  // Same keys and degree, both driven or both not (drivers themselves cannot be compared).
  bool operator==(const Track& o) const {
    return keys_ == o.keys_ && degree_ == o.degree_ && driven() == o.driven();
  }

  // Value at t; holds the first/last key outside the key range. No keys: T's zero / identity.
  T evaluate(double timeSec) const;
  // order-th time derivative at t (order 1 or 2); quaternion tracks give dq/dt as a quat.
  // Driven tracks use central differences.
  T derivative(double timeSec, int order = 1) const;

 private:
  // Derivatives (d1, d2) of key i: user values or finite differences.
  void keyDerivatives(size_t i, T& d1, T& d2) const;
  std::vector<TrackKey<T>> keys_;
  int degree_ = 2;
  Driver driver_;
};

using FloatTrack = Track<float>;
using Vec3Track = Track<glm::vec3>;
using QuatTrack = Track<glm::quat>;

extern template class Track<float>;
extern template class Track<glm::vec3>;
extern template class Track<glm::quat>;

// Automatic (Catmull-Rom finite difference) derivatives of key i of sorted
// float / vec3 keys, as Track uses them for keys without user derivatives.
template <class T>
void catmullRomDerivatives(const std::vector<TrackKey<T>>& keys, size_t i, T& d1, T& d2) {
  d1 = d2 = T(0.0f);
  size_t n = keys.size();
  if (n < 2) return;
  const auto& k = keys[i];
  if (i == 0) {
    d1 = (keys[1].value - k.value) / float(keys[1].timeSec - k.timeSec);
  } else if (i + 1 == n) {
    d1 = (k.value - keys[i - 1].value) / float(k.timeSec - keys[i - 1].timeSec);
  } else {
    const auto& a = keys[i - 1];
    const auto& b = keys[i + 1];
    float h0 = float(k.timeSec - a.timeSec), h1 = float(b.timeSec - k.timeSec);
    d1 = (b.value - a.value) / (h0 + h1);
    d2 = ((b.value - k.value) / h1 - (k.value - a.value) / h0) * (2.0f / (h0 + h1));
  }
}

// A cubic Hermite ramp from 0 at t = 0 to 1 at t = 1 with end slopes slope0
// and slope1 (0, 0: smoothstep; 0, 2: u^2; 2, 0: 1 - (1 - u)^2).
FloatTrack hermiteRampTrack(float slope0, float slope1);

}  // namespace animorph
