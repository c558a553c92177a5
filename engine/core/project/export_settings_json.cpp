#include "core/project/export_settings_json.h"

#include <initializer_list>

#include "core/project/project_io.h"
#include "core/util/json_text.h"

namespace animorph {

namespace {
struct IntField {
  const char* key;
  int* value;
  long long lo, hi;
};
struct BoolField {
  const char* key;
  bool* value;
};

// The fields both sections share (frame range, resolution, output) and their own ones, read from
// j into the settings; "" or the error (at.KEY: why).
std::string readFields(const nlohmann::json& j, const std::string& at, std::initializer_list<BoolField> bools,
                       std::initializer_list<IntField> ints, std::string& output) {
  for (const BoolField& f : bools) {
    if (!j.contains(f.key)) continue;
    if (!j[f.key].is_boolean()) return at + "." + f.key + ": expected true or false";
    *f.value = j[f.key].get<bool>();
  }
  for (const IntField& f : ints) {
    if (!j.contains(f.key)) continue;
    std::string why;
    auto v = jsonInteger(j[f.key], f.lo, f.hi, why);
    if (!v) return at + "." + f.key + ": " + why;
    *f.value = int(*v);
  }
  if (j.contains("output")) {
    if (!j["output"].is_string()) return at + ".output: expected a string";
    output = j["output"].get<std::string>();
  }
  return {};
}
}  // namespace

nlohmann::json exportSettingsToJson(const ExportSettings& s) {
  return {{"format", exportFormatName(s.format)}, {"use_timeline", s.useTimeline}, {"first", s.first},
          {"last", s.last}, {"resolution", s.resolution}, {"output", s.output}};
}

Result<ExportSettings> exportSettingsFromJson(const nlohmann::json& j, const std::string& sourceName) {
  const std::string at = sourceName + ": export";
  if (!j.is_object()) return Error{at + ": expected an object"};
  ExportSettings s;
  if (j.contains("format")) {
    const auto& f = j["format"];
    if (!f.is_string() || !exportFormatFromName(f.get<std::string>(), s.format))
      return Error{at + ".format: expected \"gltf\", \"ply\", \"obj\" or \"vdb\""};
  }
  if (std::string e = readFields(j, at, {{"use_timeline", &s.useTimeline}},
                                 {{"first", &s.first, -kMaxFrame, kMaxFrame},
                                  {"last", &s.last, -kMaxFrame, kMaxFrame},
                                  {"resolution", &s.resolution, 2, 1024}},
                                 s.output);
      !e.empty())
    return Error{e};
  if (s.last < s.first) return Error{at + ".last: is before first"};
  return s;
}

nlohmann::json playblastSettingsToJson(const PlayblastSettings& s) {
  return {{"use_timeline", s.useTimeline}, {"first", s.first},   {"last", s.last},      {"resolution", s.resolution},
          {"width", s.width},              {"height", s.height}, {"burn_in", s.burnIn}, {"viewport_camera", s.viewportCamera}, {"output", s.output}};
}

Result<PlayblastSettings> playblastSettingsFromJson(const nlohmann::json& j, const std::string& sourceName) {
  const std::string at = sourceName + ": playblast";
  if (!j.is_object()) return Error{at + ": expected an object"};
  PlayblastSettings s;
  if (std::string e = readFields(j, at, {{"use_timeline", &s.useTimeline}, {"burn_in", &s.burnIn}, {"viewport_camera", &s.viewportCamera}},
                                 {{"first", &s.first, -kMaxFrame, kMaxFrame},
                                  {"last", &s.last, -kMaxFrame, kMaxFrame},
                                  {"resolution", &s.resolution, 2, 1024},
                                  {"width", &s.width, 16, 8192},
                                  {"height", &s.height, 16, 8192}},
                                 s.output);
      !e.empty())
    return Error{e};
  if (s.last < s.first) return Error{at + ".last: is before first"};
  if (s.width % 2) return Error{at + ".width: expected an even number (H.264 needs even sizes)"};
  if (s.height % 2) return Error{at + ".height: expected an even number (H.264 needs even sizes)"};
  return s;
}

}  // namespace animorph
