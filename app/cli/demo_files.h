#pragma once
// Writing demo files: the output directory from the command line, and JSON with floats in their shortest decimal form (demo projects): a number
// that holds a float is written as the shortest text that reads back as the same
// float ("0.28", not "0.2800000011920929"), so files are small and load unchanged.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/result.h"

namespace animorph::cli {

void shortenFloats(nlohmann::json& j);
Status writeCompact(nlohmann::json j, const std::filesystem::path& path);
// The one directory among a command's arguments, created if missing; prints the
// error for `command` and returns false otherwise.
bool outputDirectory(const char* command, const std::vector<std::string>& dirs, std::filesystem::path& dir);

}  // namespace animorph::cli
