#pragma once
// Crash-safe file writes: write a temporary beside the target, fsync it,
// rename it over the target, fsync the directory. A failure at any step
// leaves the previous file untouched.
#include <string>
#include <string_view>

#include "util/result.h"

namespace animorph {

Status writeFileAtomic(const std::string& path, std::string_view contents);

// Whole file as a string; the error names the file and the reason.
Result<std::string> readFile(const std::string& path);

}  // namespace animorph
