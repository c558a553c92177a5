#pragma once
// The "morph" section of a project file (docs/morph.md describes the fields).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/project/morph_setup.h"
#include "core/util/result.h"

namespace animorph {

nlohmann::json morphSetupToJson(const MorphSetup& m);

// Parses the section. actorIds are the project's actors: source, target and
// per-actor entries must name one of them. Errors: "<source>: morph.markers.B:
// is before A".
Result<MorphSetup> morphSetupFromJson(const nlohmann::json& j, const std::string& sourceName,
                                      const std::vector<std::string>& actorIds);

}  // namespace animorph
