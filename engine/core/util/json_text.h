#pragma once
// JSON text read from files. nlohmann::json builds a document of any depth and
// the readers that walk it recurse, so a file nesting arrays 100,000 deep would
// overflow the stack: the depth is bounded by a non-recursive scan of the text
// (strings and escapes respected) before any parser sees it. Syntax errors give
// the line and column.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "core/util/result.h"

namespace animorph {

// Deepest nesting of arrays and objects accepted in any JSON file we read
// (projects, BlobTree scenes, stand-ins, preferences, the JSON of a glTF).
inline constexpr int kMaxJsonDepth = 256;

// When `text` nests arrays/objects deeper than maxDepth, a description of the
// first place it does ("nesting deeper than 256 levels at line 1, column 300
// (in /actors/0/blobtree/root/children/0/...)"); otherwise nullopt. Linear
// time, memory bounded by maxDepth; malformed text is left to the parser.
std::optional<std::string> jsonDepthError(std::string_view text, int maxDepth = kMaxJsonDepth);

// Checks the depth, then parses. Errors read "SOURCE: not valid JSON: syntax
// error at line 3, column 7: ..." or "SOURCE: nesting deeper than ...".
Result<nlohmann::json> parseJsonText(std::string_view text, const std::string& source, int maxDepth = kMaxJsonDepth);

// The value of j when it is an integer in [lo, hi], read as 64 bits (never
// through a narrower type, so 4294967297 is not 1); otherwise nullopt and
// `why` says what is wrong ("expected an integer", "4294967297 is out of
// range (0..65535)").
std::optional<long long> jsonInteger(const nlohmann::json& j, long long lo, long long hi, std::string& why);

}  // namespace animorph
