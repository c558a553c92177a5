#include "core/anim/track_json.h"

#include <cmath>
#include <string>

#include "core/util/json_text.h"

namespace animorph {

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
