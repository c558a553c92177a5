#pragma once
// Reading a JSON document's fields with errors that say where: "SOURCE: actors[1].speed: expected
// a number". The first problem is kept (later reads return their defaults), so a reader walks the
// whole document and the caller checks failed() once. Used by the project file and the morph
// set-up's JSON.
#include <cmath>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/util/json_text.h"

namespace animorph {

class JsonFieldReader {
 public:
  using json = nlohmann::json;
  explicit JsonFieldReader(std::string source) : source_(std::move(source)) {}

  bool failed() const { return !error_.empty(); }
  bool ok() const { return error_.empty(); }
  // "SOURCE: WHERE: WHY" of the first problem; empty when none.
  const std::string& error() const { return error_; }
  const std::string& source() const { return source_; }
  // Records a problem at where (a path such as "morph.markers.a") unless one is recorded already.
  void fail(const std::string& where, const std::string& why) {
    if (error_.empty()) error_ = source_ + ": " + where + ": " + why;
  }
  // Records an error that already names its place ("SOURCE: " is put in front).
  void failWith(const std::string& placedError) {
    if (error_.empty()) error_ = source_ + ": " + placedError;
  }

  // j[key] as a finite number; def when absent; def and a problem when not a finite number.
  double number(const json& j, const char* key, const std::string& where, double def) {
    if (!j.contains(key)) return def;
    const json& v = j[key];
    if (!v.is_number()) { fail(where + "." + key, "expected a number"); return def; }
    const double d = v.get<double>();
    if (!std::isfinite(d)) { fail(where + "." + key, "not a finite number"); return def; }
    return d;
  }
  // j[key] as an integer in [lo, hi] (never wrapped); def when absent.
  int integer(const json& j, const char* key, const std::string& where, int def, int lo, int hi) {
    if (!j.contains(key)) return def;
    std::string why;
    auto v = jsonInteger(j[key], lo, hi, why);
    if (!v) { fail(where + "." + key, why); return def; }
    return static_cast<int>(*v);
  }
  bool boolean(const json& j, const char* key, const std::string& where, bool def) {
    if (!j.contains(key)) return def;
    if (!j[key].is_boolean()) { fail(where + "." + key, "expected true or false"); return def; }
    return j[key].get<bool>();
  }
  // j[key] as a string; def when absent (and a problem when required).
  std::string string(const json& j, const char* key, const std::string& where, const std::string& def,
                     bool required = false) {
    if (!j.contains(key)) {
      if (required) fail(where + "." + key, "missing");
      return def;
    }
    if (!j[key].is_string()) { fail(where + "." + key, "expected a string"); return def; }
    return j[key].get<std::string>();
  }
  // A string that must be there.
  std::string requiredString(const json& j, const char* key, const std::string& where) {
    return string(j, key, where, {}, true);
  }
  // j[key] as N finite numbers; def when absent.
  template <int N>
  glm::vec<N, float> vec(const json& j, const char* key, const std::string& where, glm::vec<N, float> def) {
    if (!j.contains(key)) return def;
    const json& v = j[key];
    if (!v.is_array() || v.size() != N) {
      fail(where + "." + key, "expected an array of " + std::to_string(N) + " numbers");
      return def;
    }
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) {
        fail(where + "." + key + "[" + std::to_string(i) + "]", "expected a finite number");
        return def;
      }
      out[i] = v[i].get<float>();
    }
    return out;
  }
  // j[key] read by parse (a Result-returning reader of a nested value, given its place); def when
  // absent or when parse fails (its error recorded).
  template <class R>
  auto nested(const json& j, const char* key, const std::string& where, R (*parse)(const json&, const std::string&),
              decltype(std::declval<R>().value()) def) {
    if (!j.contains(key)) return def;
    R r = parse(j[key], where + "." + key);
    if (!r) {
      failWith(r.error());
      return def;
    }
    return r.value();
  }

 private:
  std::string source_;
  std::string error_;
};

}  // namespace animorph
