#pragma once
// Tracks to and from JSON (project files, BlobTree scenes, morph set-ups). Kept out of track.h so
// that the many files that evaluate tracks do not parse nlohmann/json.
#include <string>

#include <nlohmann/json.hpp>

#include "core/anim/track.h"
#include "core/util/result.h"

namespace animorph {

// JSON: a constant track is written as its bare value (number, [x,y,z], or
// quaternion [x,y,z,w]); otherwise {"degree": n, "keys": [{"t", "v", "interp",
// "d1", "d2"}]}. A driver is not serialised: its keys (if any) are written.
nlohmann::json trackToJson(const FloatTrack& t);
nlohmann::json trackToJson(const Vec3Track& t);
nlohmann::json trackToJson(const QuatTrack& t);

// Parse a track; errors name `where` (e.g. "node 4 parameter 'radius'") and the reason,
// including non-finite numbers and unsorted keys.
Result<FloatTrack> floatTrackFromJson(const nlohmann::json& j, const std::string& where);
Result<Vec3Track> vec3TrackFromJson(const nlohmann::json& j, const std::string& where);
Result<QuatTrack> quatTrackFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace animorph
