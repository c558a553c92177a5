#include "anim/track.h"

#include <algorithm>
#include <cmath>

#include "util/json_text.h"

namespace animorph {

namespace {

// Per-type helpers so one implementation serves float and vec3 (linear spaces).
template <class T>
T zeroOf() {
  if constexpr (std::is_same_v<T, glm::quat>) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  else return T(0.0f);
}

glm::quat shortArc(const glm::quat& from, const glm::quat& to) { return glm::dot(from, to) < 0.0f ? -to : to; }

// Slerp of unit quaternions along the shortest arc, stable near equal inputs.
glm::quat slerpShort(const glm::quat& a, const glm::quat& bIn, float s) {
  glm::quat b = shortArc(a, bIn);
  float c = glm::clamp(glm::dot(a, b), -1.0f, 1.0f);
  if (c > 0.9995f) return glm::normalize(a * (1.0f - s) + b * s);
  float theta = std::acos(c);
  float sn = std::sin(theta);
  return glm::normalize(a * (std::sin((1.0f - s) * theta) / sn) + b * (std::sin(s * theta) / sn));
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
    T dp = k1.value - k0.value;
    T c[6];
    c[0] = k0.value;
    c[1] = v0 * h;
    if (degree_ == 2) {
      c[2] = dp * 3.0f - v0 * (2.0f * h) - v1 * h;
      c[3] = dp * -2.0f + v0 * h + v1 * h;
      return c[0] + s * (c[1] + s * (c[2] + s * c[3]));
    }
    float h2 = h * h;
    c[2] = a0 * (0.5f * h2);
    c[3] = dp * 10.0f - v0 * (6.0f * h) - v1 * (4.0f * h) - a0 * (1.5f * h2) + a1 * (0.5f * h2);
    c[4] = dp * -15.0f + v0 * (8.0f * h) + v1 * (7.0f * h) + a0 * (1.5f * h2) - a1 * h2;
    c[5] = dp * 6.0f - v0 * (3.0f * h) - v1 * (3.0f * h) - a0 * (0.5f * h2) + a1 * (0.5f * h2);
    return c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))));
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
    T dp = k1.value - k0.value;
    T c[6];
    int deg = degree_ == 2 ? 3 : 5;
    c[0] = k0.value;
    c[1] = v0 * h;
    float h2 = h * h;
    if (degree_ == 2) {
      c[2] = dp * 3.0f - v0 * (2.0f * h) - v1 * h;
      c[3] = dp * -2.0f + v0 * h + v1 * h;
    } else {
      c[2] = a0 * (0.5f * h2);
      c[3] = dp * 10.0f - v0 * (6.0f * h) - v1 * (4.0f * h) - a0 * (1.5f * h2) + a1 * (0.5f * h2);
      c[4] = dp * -15.0f + v0 * (8.0f * h) + v1 * (7.0f * h) + a0 * (1.5f * h2) - a1 * h2;
      c[5] = dp * 6.0f - v0 * (3.0f * h) - v1 * (3.0f * h) - a0 * (0.5f * h2) + a1 * (0.5f * h2);
    }
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

// ---------------------------------------------------------------- JSON

namespace {

using nlohmann::json;

json valueToJson(float v) { return v; }
json valueToJson(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }
json valueToJson(const glm::quat& q) { return json::array({q.x, q.y, q.z, q.w}); }

const char* interpName(KeyInterp i) {
  switch (i) {
    case KeyInterp::Constant: return "constant";
    case KeyInterp::Linear: return "linear";
    case KeyInterp::Hermite: return "hermite";
  }
  return "hermite";
}

template <class T>
json toJsonImpl(const Track<T>& t) {
  const auto& keys = t.keys();
  if (keys.size() == 1 && !keys[0].userDerivatives) return valueToJson(keys[0].value);
  json arr = json::array();
  for (const auto& k : keys) {
    json jk = {{"t", k.timeSec}, {"v", valueToJson(k.value)}};
    if (k.interp != KeyInterp::Hermite) jk["interp"] = interpName(k.interp);
    if constexpr (!std::is_same_v<T, glm::quat>) {
      if (k.userDerivatives) {
        jk["d1"] = valueToJson(k.d1);
        if (t.degree() == 3) jk["d2"] = valueToJson(k.d2);
      }
    }
    arr.push_back(jk);
  }
  json j = {{"keys", arr}};
  if (t.degree() != 2) j["degree"] = t.degree();
  return j;
}

bool readNumber(const json& j, float& out) {
  if (!j.is_number()) return false;
  double d = j.get<double>();
  if (!std::isfinite(d)) return false;
  out = float(d);
  return std::isfinite(out);
}

std::string describe(const json& j) {
  if (j.is_number()) {
    double d = j.get<double>();
    if (std::isnan(d)) return "NaN";
    if (std::isinf(d)) return "infinity";
  }
  if (j.is_null()) return "null (not a number)";
  std::string s = j.dump();
  return s.size() > 40 ? s.substr(0, 40) + "..." : s;
}

bool readValue(const json& j, float& v, std::string& err) {
  if (readNumber(j, v)) return true;
  err = "expected a finite number, got " + describe(j);
  return false;
}

bool readValue(const json& j, glm::vec3& v, std::string& err) {
  if (j.is_array() && j.size() == 3 && readNumber(j[0], v.x) && readNumber(j[1], v.y) && readNumber(j[2], v.z))
    return true;
  err = "expected [x, y, z] of finite numbers, got " + describe(j);
  return false;
}

bool readValue(const json& j, glm::quat& q, std::string& err) {
  if (j.is_array() && j.size() == 4 && readNumber(j[0], q.x) && readNumber(j[1], q.y) && readNumber(j[2], q.z) &&
      readNumber(j[3], q.w)) {
    float len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    if (len < 1e-6f) {
      err = "quaternion [x, y, z, w] has zero length";
      return false;
    }
    if (std::abs(len - 1.0f) > 1e-6f) q = glm::normalize(q);  // idempotent on unit input
    return true;
  }
  err = "expected a quaternion [x, y, z, w] of finite numbers, got " + describe(j);
  return false;
}

template <class T>
Result<Track<T>> fromJsonImpl(const json& j, const std::string& where) {
  std::string err;
  if (!j.is_object()) {
    T v;
    if (!readValue(j, v, err)) return Error{where + ": " + err};
    return Track<T>(v);
  }
  Track<T> track;
  track.clearKeys();
  if (j.contains("degree")) {
    std::string why;
    if (!jsonInteger(j["degree"], 2, 3, why))
      return Error{where + ": \"degree\" must be 2 (cubic) or 3 (quintic)"};
    track.setDegree(j["degree"].get<int>());
  }
  if (!j.contains("keys") || !j["keys"].is_array() || j["keys"].empty())
    return Error{where + ": expected a value or {\"keys\": [...]} with at least one key"};
  double prev = -INFINITY;
  for (size_t i = 0; i < j["keys"].size(); ++i) {
    const json& jk = j["keys"][i];
    std::string kw = where + " key " + std::to_string(i);
    if (!jk.is_object() || !jk.contains("t") || !jk.contains("v"))
      return Error{kw + ": a key needs \"t\" (seconds) and \"v\" (value)"};
    float tt;
    if (!readNumber(jk["t"], tt)) return Error{kw + ": \"t\" " + "must be a finite number, got " + describe(jk["t"])};
    double t = jk["t"].get<double>();
    if (t <= prev) return Error{kw + ": key times must increase (" + std::to_string(t) + " after " +
                                std::to_string(prev) + ")"};
    prev = t;
    TrackKey<T> key;
    key.timeSec = t;
    if (!readValue(jk["v"], key.value, err)) return Error{kw + " \"v\": " + err};
    if (jk.contains("interp")) {
      std::string s = jk["interp"].is_string() ? jk["interp"].get<std::string>() : "";
      if (s == "constant") key.interp = KeyInterp::Constant;
      else if (s == "linear") key.interp = KeyInterp::Linear;
      else if (s == "hermite") key.interp = KeyInterp::Hermite;
      else return Error{kw + ": \"interp\" must be \"constant\", \"linear\" or \"hermite\""};
    }
    if constexpr (!std::is_same_v<T, glm::quat>) {
      if (jk.contains("d1")) {
        key.userDerivatives = true;
        if (!readValue(jk["d1"], key.d1, err)) return Error{kw + " \"d1\": " + err};
        if (jk.contains("d2") && !readValue(jk["d2"], key.d2, err)) return Error{kw + " \"d2\": " + err};
      }
    }
    track.keys().push_back(key);
  }
  return track;
}

}  // namespace

nlohmann::json trackToJson(const FloatTrack& t) { return toJsonImpl(t); }
nlohmann::json trackToJson(const Vec3Track& t) { return toJsonImpl(t); }
nlohmann::json trackToJson(const QuatTrack& t) { return toJsonImpl(t); }

Result<FloatTrack> floatTrackFromJson(const nlohmann::json& j, const std::string& where) {
  return fromJsonImpl<float>(j, where);
}
Result<Vec3Track> vec3TrackFromJson(const nlohmann::json& j, const std::string& where) {
  return fromJsonImpl<glm::vec3>(j, where);
}
Result<QuatTrack> quatTrackFromJson(const nlohmann::json& j, const std::string& where) {
  return fromJsonImpl<glm::quat>(j, where);
}

}  // namespace animorph
