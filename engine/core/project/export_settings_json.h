#pragma once
// The "export" and "playblast" sections of a project file; every field optional.
//   export:    {"format": "gltf"|"ply"|"obj"|"vdb", "use_timeline": bool, "first": int, "last": int,
//               "resolution": int, "output": string}
//   playblast: {"use_timeline": bool, "first": int, "last": int, "resolution": int, "width": int,
//               "height": int, "burn_in": bool, "output": string}
#include <string>

#include <nlohmann/json.hpp>

#include "core/project/export_settings.h"
#include "core/project/playblast_settings.h"
#include "core/util/result.h"

namespace animorph {

nlohmann::json exportSettingsToJson(const ExportSettings& s);
// Errors name the source and the field: "<source>: export.resolution: expected 2..1024".
Result<ExportSettings> exportSettingsFromJson(const nlohmann::json& j, const std::string& sourceName);

nlohmann::json playblastSettingsToJson(const PlayblastSettings& s);
// Errors name the source and the field: "<source>: playblast.width: expected an even number".
Result<PlayblastSettings> playblastSettingsFromJson(const nlohmann::json& j, const std::string& sourceName);

}  // namespace animorph
