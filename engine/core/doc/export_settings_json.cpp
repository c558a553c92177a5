#include "doc/export_settings_json.h"

#include "doc/project_io.h"
#include "util/json_text.h"

namespace animorph {

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
  if (j.contains("use_timeline")) {
    if (!j["use_timeline"].is_boolean()) return Error{at + ".use_timeline: expected true or false"};
    s.useTimeline = j["use_timeline"].get<bool>();
  }
  struct IntField {
    const char* key;
    int* value;
    long long lo, hi;
  };
  for (const IntField& f : {IntField{"first", &s.first, -kMaxFrame, kMaxFrame},
                            IntField{"last", &s.last, -kMaxFrame, kMaxFrame},
                            IntField{"resolution", &s.resolution, 2, 1024}}) {
    if (!j.contains(f.key)) continue;
    std::string why;
    auto v = jsonInteger(j[f.key], f.lo, f.hi, why);
    if (!v) return Error{at + "." + f.key + ": " + why};
    *f.value = int(*v);
  }
  if (s.last < s.first) return Error{at + ".last: is before first"};
  if (j.contains("output")) {
    if (!j["output"].is_string()) return Error{at + ".output: expected a string"};
    s.output = j["output"].get<std::string>();
  }
  return s;
}

}  // namespace animorph
