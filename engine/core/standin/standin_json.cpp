#include "core/standin/standin_json.h"

#include <cmath>
#include <limits>

#include "core/util/atomic_file.h"
#include "core/util/json_text.h"

namespace animorph {

using json = nlohmann::json;

namespace {

json vec3Json(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

bool readVec3(const json& j, glm::vec3& out) {
  if (!j.is_array() || j.size() != 3) return false;
  for (int i = 0; i < 3; ++i) {
    if (!j[size_t(i)].is_number()) return false;
    const double d = j[size_t(i)].get<double>();
    // Finite as a float too: 1e306 would become inf, and the saved file would not load.
    if (!std::isfinite(d) || std::abs(d) > double(std::numeric_limits<float>::max())) return false;
    out[i] = float(d);
  }
  return true;
}

}  // namespace

json standinToJson(const Standin& s) {
  json segs = json::array();
  for (const auto& seg : s.segments)
    segs.push_back({{"node", seg.node}, {"a", vec3Json(seg.a)}, {"b", vec3Json(seg.b)}, {"radius", seg.radius}});
  return {{"kind", standinKindName(s.kind)}, {"sharpness", s.sharpness}, {"segments", segs}};
}

Result<Standin> standinFromJson(const json& j, const std::string& where) {
  if (!j.is_object()) return Error{where + ": expected an object"};
  Standin s;
  if (j.contains("kind")) {
    const json& k = j["kind"];
    if (k == "convolution") s.kind = StandinKind::Convolution;
    else if (k == "capsule_union") s.kind = StandinKind::CapsuleUnion;
    else if (k == "capsule_blend") s.kind = StandinKind::CapsuleBlend;
    else return Error{where + ".kind: expected \"convolution\", \"capsule_union\" or \"capsule_blend\""};
  }
  if (j.contains("sharpness")) {
    if (!j["sharpness"].is_number() || !(j["sharpness"].get<double>() > 0.0) ||
        !std::isfinite(j["sharpness"].get<double>()))
      return Error{where + ".sharpness: must be a positive number"};
    s.sharpness = j["sharpness"].get<float>();
  }
  if (!j.contains("segments") || !j["segments"].is_array()) return Error{where + ".segments: missing or not an array"};
  const json& segs = j["segments"];
  for (size_t i = 0; i < segs.size(); ++i) {
    const std::string w = where + ".segments[" + std::to_string(i) + "]";
    const json& e = segs[i];
    if (!e.is_object()) return Error{w + ": expected an object"};
    StandinSegment seg;
    if (!e.contains("node") || !e["node"].is_number_integer() || e["node"].get<long long>() < 0 ||
        e["node"].get<long long>() > 1000000)
      return Error{w + ".node: expected a node index (integer >= 0)"};
    seg.node = e["node"].get<int>();
    if (!e.contains("a") || !readVec3(e["a"], seg.a)) return Error{w + ".a: expected an array of 3 finite numbers (within +-3.4e38)"};
    if (!e.contains("b") || !readVec3(e["b"], seg.b)) return Error{w + ".b: expected an array of 3 finite numbers (within +-3.4e38)"};
    if (!e.contains("radius") || !e["radius"].is_number() || !std::isfinite(e["radius"].get<double>()) ||
        !(e["radius"].get<double>() > 0.0) || e["radius"].get<double>() > double(std::numeric_limits<float>::max()))
      return Error{w + ".radius: must be a positive number (metres)"};
    seg.radius = e["radius"].get<float>();
    s.segments.push_back(seg);
  }
  return s;
}

std::string standinFileText(const Standin& s, const std::string& characterPath, const json& report) {
  json j = {{"format", "animorph-standin"},
            {"version", 1},
            {"character", characterPath},
            {"standin", standinToJson(s)},
            {"report", report}};
  return j.dump(2) + "\n";
}

Result<Standin> loadStandinFile(const std::string& path) {
  auto text = readFile(path);
  if (!text) return Error{text.error()};
  auto parsed = parseJsonText(*text, path);
  if (!parsed) return Error{parsed.error()};
  const json& j = *parsed;
  if (!j.is_object()) return Error{path + ": expected a JSON object at the top level"};
  if (!j.contains("format") || j["format"] != "animorph-standin")
    return Error{path + ": not a stand-in file (missing \"format\": \"animorph-standin\")"};
  std::string why;
  if (!j.contains("version") || !jsonInteger(j["version"], 1, 1, why)) return Error{path + ": version: expected 1"};
  if (!j.contains("standin")) return Error{path + ": standin: missing"};
  return standinFromJson(j["standin"], path + ": standin");
}

}  // namespace animorph
