#include "core/project/animorphosis_setup_json.h"

#include <cmath>

#include "core/animorphosis/correspondence_json.h"
#include "core/anim/track_json.h"

namespace animorph {

using nlohmann::json;

json animorphosisSetupToJson(const AnimorphosisSetup& a) {
  json j{{"source", a.sourceActorId}, {"target", a.targetActorId}, {"start", a.startSec},
         {"end", a.endSec},           {"s", trackToJson(a.globalS)},  {"graph", correspondenceToJson(a.graph)}};
  if (a.showGhosts) j["ghosts"] = true;
  return j;
}

Result<AnimorphosisSetup> animorphosisSetupFromJson(const json& j, const std::string& sourceName) {
  const std::string at = sourceName + ": animorphosis";
  if (!j.is_object()) return Error{at + ": expected an object"};
  AnimorphosisSetup a;
  for (const char* key : {"source", "target"}) {
    auto it = j.find(key);
    if (it == j.end() || !it->is_string() || it->get<std::string>().empty())
      return Error{at + "." + key + ": missing or not an actor id"};
    (std::string(key) == "source" ? a.sourceActorId : a.targetActorId) = it->get<std::string>();
  }
  for (const char* key : {"start", "end"}) {
    auto it = j.find(key);
    if (it == j.end() || !it->is_number() || !std::isfinite(it->get<double>()))
      return Error{at + "." + key + ": missing or not a number (seconds)"};
    (std::string(key) == "start" ? a.startSec : a.endSec) = it->get<double>();
  }
  if (!(a.endSec > a.startSec)) return Error{at + ".end: must be after start"};
  if (auto it = j.find("s"); it != j.end()) {
    auto s = floatTrackFromJson(*it, at + ".s");
    if (!s) return Error{s.error()};
    if (Status ok = checkSCurve(*s, at + ".s"); !ok) return Error{ok.error()};
    a.globalS = std::move(*s);
  }
  if (auto it = j.find("ghosts"); it != j.end()) {
    if (!it->is_boolean()) return Error{at + ".ghosts: not true or false"};
    a.showGhosts = it->get<bool>();
  }
  if (auto it = j.find("graph"); it != j.end()) {
    auto g = correspondenceFromJson(*it, at + ".graph");
    if (!g) return Error{g.error()};
    a.graph = std::move(*g);
  }
  return a;
}

}  // namespace animorph
