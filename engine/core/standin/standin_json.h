#pragma once
// JSON form of a stand-in (inside a project's "morph" section, or a file of
// its own written by `animorph-cli fit`).
#include <string>

#include <nlohmann/json.hpp>

#include "core/standin/standin.h"
#include "core/util/result.h"

namespace animorph {

// {"kind", "sharpness", "segments": [{"node", "a", "b", "radius"}]}.
nlohmann::json standinToJson(const Standin& s);

// Parses what standinToJson writes. Errors: "<where>.segments[3].radius: must be positive".
Result<Standin> standinFromJson(const nlohmann::json& j, const std::string& where);

// A stand-in file: {"format": "animorph-standin", "version": 1, "character", "standin", "report"}.
std::string standinFileText(const Standin& s, const std::string& characterPath, const nlohmann::json& report);

// Reads a stand-in file; errors name the file and the element.
Result<Standin> loadStandinFile(const std::string& path);

}  // namespace animorph
