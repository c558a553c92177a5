#pragma once
// Correspondence graph JSON:
//   {"links": [{"a": ID, "b": ID, "confidence": 0..1, "artist": bool, "s": TRACK}, ...],
//    "suggestions": [{"a": ID, "b": ID, "confidence": 0..1}, ...]}
// "suggestions" (proposed, not applied) is optional and written only when there are some.
// "s" (the link's s(u) override, a float track) is optional; "confidence"
// defaults to 1 and "artist" to true. Structure only: validateCorrespondence
// checks the ids against the trees.
#include <string>

#include <nlohmann/json.hpp>

#include "core/animorphosis/correspondence.h"
#include "core/util/result.h"

namespace animorph {

inline constexpr size_t kMaxCorrespondenceLinks = 1000000;

nlohmann::json correspondenceToJson(const CorrespondenceGraph& g);
// Errors start with `source` and name the link index and the field: missing or
// non-integer ids, confidence outside [0, 1], a bad s curve, too many links.
Result<CorrespondenceGraph> correspondenceFromJson(const nlohmann::json& j, const std::string& source);

}  // namespace animorph
