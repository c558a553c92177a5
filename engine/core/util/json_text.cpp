#include "core/util/json_text.h"

#include <vector>

namespace animorph {
namespace {

// One open array or object while scanning.
struct Level {
  bool array = false;
  bool expectKey = false;  // objects: the next string is a key
  size_t index = 0;        // arrays: element number
  std::string key;         // objects: the current key (truncated)
};

std::string pointerSegment(const Level& l) {
  if (l.array) return std::to_string(l.index);
  std::string s;
  for (char c : l.key) {
    if (c == '~') s += "~0";
    else if (c == '/') s += "~1";
    else s += c;
  }
  return s;
}

// JSON pointer of the innermost value, shortened in the middle when long.
// An object just opened has no key yet: the pointer ends at the object.
std::string pointerOf(const std::vector<Level>& levels) {
  constexpr size_t kHead = 8, kTail = 3;
  size_t n = levels.size();
  if (n > 0 && !levels.back().array && levels.back().key.empty()) --n;
  std::string out;
  for (size_t i = 0; i < n; ++i) {
    if (n > kHead + kTail && i == kHead) {
      out += "/...";
      i = n - kTail - 1;
      continue;
    }
    out += "/" + pointerSegment(levels[i]);
  }
  return out.empty() ? "/" : out;
}

}  // namespace

std::optional<std::string> jsonDepthError(std::string_view text, int maxDepth) {
  constexpr size_t kMaxKeyChars = 64;
  std::vector<Level> levels;
  levels.reserve(static_cast<size_t>(maxDepth) + 1);
  size_t line = 1, column = 0;
  bool inString = false, escaped = false, collecting = false;
  std::string str;
  for (char c : text) {
    if (c == '\n') {
      ++line;
      column = 0;
    } else {
      ++column;
    }
    if (inString) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        inString = false;
        if (collecting) {
          levels.back().key = str;
          levels.back().expectKey = false;
          collecting = false;
        }
        continue;
      }
      if (collecting && str.size() < kMaxKeyChars) str += c;
      continue;
    }
    switch (c) {
      case '"':
        inString = true;
        collecting = !levels.empty() && !levels.back().array && levels.back().expectKey;
        str.clear();
        break;
      case '[':
      case '{':
        levels.push_back(Level{c == '[', c == '{', 0, {}});
        if (static_cast<int>(levels.size()) > maxDepth)
          return "nesting deeper than " + std::to_string(maxDepth) + " levels at line " + std::to_string(line) +
                 ", column " + std::to_string(column) + " (in " + pointerOf(levels) + ")";
        break;
      case ']':
      case '}':
        if (!levels.empty()) levels.pop_back();
        break;
      case ',':
        if (!levels.empty()) {
          if (levels.back().array) ++levels.back().index;
          else levels.back().expectKey = true;
        }
        break;
      default: break;
    }
  }
  return std::nullopt;
}

Result<nlohmann::json> parseJsonText(std::string_view text, const std::string& source, int maxDepth) {
  if (auto deep = jsonDepthError(text, maxDepth)) return Error{source + ": " + *deep};
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.parse_error.101] parse error at line 1, column 2: ..."
    std::string what = e.what();
    if (auto close = what.find("] "); what.rfind("[json.exception", 0) == 0 && close != std::string::npos)
      what.erase(0, close + 2);
    return Error{source + ": not valid JSON: " + what};
  }
}

std::optional<long long> jsonInteger(const nlohmann::json& j, long long lo, long long hi, std::string& why) {
  if (!j.is_number_integer()) {
    why = "expected an integer";
    return std::nullopt;
  }
  const auto range = [&] { return " is out of range (" + std::to_string(lo) + ".." + std::to_string(hi) + ")"; };
  if (j.is_number_unsigned()) {
    const auto u = j.get<unsigned long long>();
    if (hi < 0 || u > static_cast<unsigned long long>(hi)) {
      why = std::to_string(u) + range();
      return std::nullopt;
    }
    if (static_cast<long long>(u) < lo) {
      why = std::to_string(u) + range();
      return std::nullopt;
    }
    return static_cast<long long>(u);
  }
  const auto v = j.get<long long>();
  if (v < lo || v > hi) {
    why = std::to_string(v) + range();
    return std::nullopt;
  }
  return v;
}

}  // namespace animorph
