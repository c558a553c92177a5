#pragma once
// *.animorph project files: JSON with "format": "animorph" and "version".
#include <string>

#include "core/project/project.h"
#include "core/util/job_progress.h"
#include "core/util/result.h"

namespace animorph {

// Ranges a project file is held to when read: frame numbers (timeline,
// morph markers) stay within +-kMaxFrame so that differences and sums of
// them cannot overflow an int; clip indices below kMaxClipIndex; frame
// rates in [kMinFps, kMaxFps].
inline constexpr int kMaxFrame = 10'000'000;
inline constexpr int kMaxClipIndex = 65'535;
inline constexpr double kMinFps = 0.1;
inline constexpr double kMaxFps = 1000.0;

// Serialises p as pretty-printed JSON.
std::string projectToJson(const Project& p);

// Parses a project. sourceName is used in error messages ("demo.animorph:
// actors[1].speed: expected a number"). Newer format versions are refused.
Result<Project> projectFromJson(const std::string& text, const std::string& sourceName);

// Reads and parses a project file. With progress: the stages "reading" and "parsing", the file's
// bytes counted once read and four times more once parsed (parsing takes about that much longer);
// cancel is polled while reading and before parsing.
Result<Project> loadProject(const std::string& path, JobProgress* progress = nullptr);

// Writes a project file atomically.
Status saveProject(const Project& p, const std::string& path);

}  // namespace animorph
