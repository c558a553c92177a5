#include "core/io/fbx_shape_values.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <string_view>

#include "core/io/declared_size_check.h"

namespace animorph {
namespace {

constexpr size_t kHeaderBytes = 27;    // "Kaydara FBX Binary  \0\x1a\0" and a u32 version
constexpr size_t kMaxKeptProps = 16;   // properties kept per record (the rest are walked, not kept)
constexpr size_t kMaxKeptText = 256;   // bytes kept of a string property

struct Prop {
  char type = 0;
  double number = 0.0;
  std::string text;
  bool isNumber() const { return type == 'D' || type == 'F' || type == 'I' || type == 'L' || type == 'Y' || type == 'C'; }
};

struct Record {
  size_t at = 0;
  std::string name;
  std::vector<Prop> props;
  size_t childrenBegin = 0, end = 0;
  bool null = false;  // the empty record that closes a list
};

uint64_t readLe(const std::string& b, size_t at, size_t width) {
  uint64_t v = 0;
  for (size_t i = 0; i < width; ++i) v |= uint64_t(static_cast<unsigned char>(b[at + i])) << (8 * i);
  return v;
}

template <class T>
T readAs(const std::string& b, size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}

struct BinaryReader {
  const std::string& file;
  const std::string& b;
  size_t width = 4;  // record header fields: 4 bytes, 8 from FBX 7.5

  Error fail(size_t at, const std::string& name, const std::string& reason) const {
    return Error{file + ": FBX record '" + name + "' at byte " + std::to_string(at) + ": " + reason};
  }

  // One property at p (advanced past it), within [p, end).
  Status property(size_t& p, size_t end, const Record& r, Prop& out) const {
    if (p >= end) return fail(r.at, r.name, "property list runs past the record's end");
    out.type = b[p++];
    const size_t left = end - p;
    auto number = [&](size_t n) -> Status {
      if (left < n) return fail(r.at, r.name, "a property runs past the record's end");
      switch (out.type) {
        case 'C': out.number = b[p] != 0; break;
        case 'Y': out.number = readAs<int16_t>(b, p); break;
        case 'I': out.number = readAs<int32_t>(b, p); break;
        case 'F': out.number = readAs<float>(b, p); break;
        case 'D': out.number = readAs<double>(b, p); break;
        default: out.number = double(readAs<int64_t>(b, p)); break;
      }
      p += n;
      return {};
    };
    switch (out.type) {
      case 'C': return number(1);
      case 'Y': return number(2);
      case 'I': case 'F': return number(4);
      case 'D': case 'L': return number(8);
      case 'S': case 'R': case 'f': case 'i': case 'd': case 'l': case 'b': {
        const bool array = out.type != 'S' && out.type != 'R';
        const size_t head = array ? 12 : 4;
        if (left < head) break;
        const uint64_t len = readLe(b, p + head - 4, 4);  // strings: their length; arrays: stored bytes
        if (left - head < len) break;
        if (out.type == 'S') out.text = b.substr(p + head, std::min<size_t>(len, kMaxKeptText));
        p += head + len;
        return {};
      }
      default: return fail(r.at, r.name, "unknown property type");
    }
    return fail(r.at, r.name, "a property runs past the record's end");
  }

  // The record at p, which must end by limit.
  Result<Record> read(size_t p, size_t limit) const {
    Record r;
    r.at = p;
    const size_t header = 3 * width + 1;
    if (limit < p || limit - p < header) return fail(p, "?", "record header runs past its parent's end");
    const uint64_t end = readLe(b, p, width), props = readLe(b, p + width, width), propBytes = readLe(b, p + 2 * width, width);
    const size_t nameLen = static_cast<unsigned char>(b[p + 3 * width]);
    if (end == 0) {
      r.null = true;
      r.end = p + header;
      return r;
    }
    p += header;
    if (nameLen > limit - p) return fail(r.at, "?", "name runs past its parent's end");
    r.name = b.substr(p, nameLen);
    p += nameLen;
    if (end <= r.at || end > limit) return fail(r.at, r.name, "ends at byte " + std::to_string(end) + ", outside its parent");
    if (propBytes > end - p) return fail(r.at, r.name, "its property list runs past its end");
    const size_t propEnd = p + propBytes;
    for (uint64_t i = 0; i < props; ++i) {
      Prop prop;
      if (auto st = property(p, propEnd, r, prop); !st) return Error{st.error()};
      if (r.props.size() < kMaxKeptProps) r.props.push_back(std::move(prop));
    }
    r.childrenBegin = propEnd;
    r.end = end;
    return r;
  }

  // Calls visit for each record of the list [begin, end) (depth: of that list).
  Status children(size_t begin, size_t end, int depth, const std::function<Status(const Record&)>& visit) const {
    if (depth > kFbxMaxDepth) return fail(begin, "?", "nested deeper than " + std::to_string(kFbxMaxDepth) + " records");
    for (size_t p = begin; p < end;) {
      auto r = read(p, end);
      if (!r) return Error{r.error()};
      if (r->null) break;
      if (auto st = visit(*r); !st) return st;
      p = r->end;
    }
    return {};
  }
};

// A binary object name is "NAME\0\x01CLASS"; assimp names a shape by NAME.
std::string objectName(const std::string& text) {
  const size_t sep = text.find(std::string("\0\x01", 2));
  return sep == std::string::npos ? text : text.substr(0, sep);
}

void addValue(FbxShapeValues& out, const std::string& name, double percent) {
  auto [it, inserted] = out.percentByChannel.emplace(name, percent);
  if (!inserted && it->second != percent) out.conflicting.push_back(name);
}

Result<FbxShapeValues> readBinary(const std::string& file, const std::string& b) {
  FbxShapeValues out;
  if (b.size() < kHeaderBytes) return Error{file + ": not a binary FBX file (header too short)"};
  BinaryReader reader{file, b, readLe(b, 23, 4) >= 7500 ? size_t(8) : size_t(4)};
  // Objects > Deformer (class BlendShapeChannel) > DeformPercent, or > Properties70 > P "DeformPercent".
  auto channel = [&](const Record& d) -> Status {
    if (d.name != "Deformer" || d.props.size() < 3 || d.props[2].text != "BlendShapeChannel") return {};
    const std::string name = objectName(d.props[1].text);
    std::optional<double> direct, property;
    auto field = [&](const Record& f) -> Status {
      if (f.name == "DeformPercent" && !f.props.empty() && f.props[0].isNumber()) direct = f.props[0].number;
      if (f.name != "Properties70") return {};
      return reader.children(f.childrenBegin, f.end, 3, [&](const Record& prop) -> Status {
        if (prop.name == "P" && prop.props.size() >= 5 && prop.props[0].text == "DeformPercent" &&
            prop.props.back().isNumber())
          property = prop.props.back().number;
        return {};
      });
    };
    if (auto st = reader.children(d.childrenBegin, d.end, 2, field); !st) return st;
    if (property || direct) addValue(out, name, property ? *property : *direct);
    return {};
  };
  auto top = [&](const Record& r) -> Status {
    return r.name == "Objects" ? reader.children(r.childrenBegin, r.end, 1, channel) : Status{};
  };
  if (auto st = reader.children(kHeaderBytes, b.size(), 0, top); !st) return Error{st.error()};
  return out;
}

// ASCII: Deformer: ID, "SubDeformer::NAME", "BlendShapeChannel" { ... DeformPercent: V ...
// Properties70: { P: "DeformPercent", "Number", "", "A", V } }
Result<FbxShapeValues> readAscii(const std::string& file, const std::string& b) {
  FbxShapeValues out;
  const std::string cls = "\"BlendShapeChannel\"";
  size_t p = b.find(cls);
  while (p != std::string::npos) {
    size_t next = p + cls.size();
    const size_t lineStart = b.rfind('\n', p) == std::string::npos ? 0 : b.rfind('\n', p) + 1;
    const std::string_view line(b.data() + lineStart, p - lineStart);
    const size_t q1 = line.find('"'), q2 = q1 == std::string::npos ? q1 : line.find('"', q1 + 1);
    if (line.find("Deformer:") != std::string::npos && q2 != std::string::npos) {
      std::string name(line.substr(q1 + 1, q2 - q1 - 1));
      if (const size_t colons = name.find("::"); colons != std::string::npos) name = name.substr(colons + 2);
      const size_t open = b.find('{', p);
      if (open == std::string::npos)
        return Error{file + ": blend shape channel '" + name + "' at byte " + std::to_string(p) + ": no { block }"};
      size_t close = open + 1;
      bool quoted = false;
      for (int depth = 1; close < b.size() && depth > 0; ++close) {
        if (b[close] == '"') quoted = !quoted;
        else if (!quoted && b[close] == '{') ++depth;
        else if (!quoted && b[close] == '}') --depth;
      }
      const std::string_view block(b.data() + open, close - open);
      std::optional<double> value;
      if (const size_t pp = block.find("\"DeformPercent\""); pp != std::string::npos) {
        const size_t eol = std::min(block.find('\n', pp), block.size());
        const size_t comma = block.substr(0, eol).rfind(',');
        if (comma != std::string::npos && comma > pp) value = std::strtod(b.c_str() + open + comma + 1, nullptr);
      }
      if (const size_t d = block.find("DeformPercent:"); !value && d != std::string::npos)
        value = std::strtod(b.c_str() + open + d + 14, nullptr);
      if (value && std::isfinite(*value)) addValue(out, name, *value);
      next = close;
    }
    p = b.find(cls, next);
  }
  return out;
}

}  // namespace

Result<FbxShapeValues> readFbxShapeValues(const std::string& file, const std::string& bytes) {
  return isFbxBinary(bytes) ? readBinary(file, bytes) : readAscii(file, bytes);
}

}  // namespace animorph
