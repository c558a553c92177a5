#pragma once
// Base64 (RFC 4648, with padding) of float32 arrays, little-endian: how
// weight maps are stored in project files.
#include <string>
#include <vector>

#include "core/util/result.h"

namespace animorph {

std::string floatsToBase64(const std::vector<float>& values);

// Decodes; errors (named by where): bad characters or padding, a length not a
// multiple of 4 bytes, non-finite values.
Result<std::vector<float>> floatsFromBase64(const std::string& text, const std::string& where);

}  // namespace animorph
