#pragma once
// The "animorphosis" section of a project file:
//   {"source": ACTOR_ID, "target": ACTOR_ID, "start": SEC, "end": SEC,
//    "s": TRACK, "graph": {"links": [...]}}   (graph: animorphosis/correspondence_json.h)
// Parsing checks the structure; checkAnimorphosis (project/animorphosis_project.h)
// checks it against the project's actors.
#include <string>

#include <nlohmann/json.hpp>

#include "core/project/animorphosis_setup.h"
#include "core/util/result.h"

namespace animorph {

nlohmann::json animorphosisSetupToJson(const AnimorphosisSetup& a);
// Errors: "<source>: animorphosis.end: must be after start".
Result<AnimorphosisSetup> animorphosisSetupFromJson(const nlohmann::json& j, const std::string& sourceName);

}  // namespace animorph
