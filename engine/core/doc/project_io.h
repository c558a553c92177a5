#pragma once
// *.animorph project files: JSON with "format": "animorph" and "version".
#include <string>

#include "doc/project.h"
#include "util/result.h"

namespace animorph {

// Serialises p as pretty-printed JSON.
std::string projectToJson(const Project& p);

// Parses a project. sourceName is used in error messages ("demo.animorph:
// actors[1].speed: expected a number"). Newer format versions are refused.
Result<Project> projectFromJson(const std::string& text, const std::string& sourceName);

// Reads and parses a project file.
Result<Project> loadProject(const std::string& path);

// Writes a project file atomically.
Status saveProject(const Project& p, const std::string& path);

}  // namespace animorph
