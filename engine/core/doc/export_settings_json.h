#pragma once
// The "export" section of a project file: {"format": "gltf"|"ply"|"obj", "use_timeline": bool,
// "first": int, "last": int, "resolution": int, "output": string}; every field optional.
#include <string>

#include <nlohmann/json.hpp>

#include "doc/export_settings.h"
#include "util/result.h"

namespace animorph {

nlohmann::json exportSettingsToJson(const ExportSettings& s);
// Errors name the source and the field: "<source>: export.resolution: expected 2..1024".
Result<ExportSettings> exportSettingsFromJson(const nlohmann::json& j, const std::string& sourceName);

}  // namespace animorph
