#include "core/io/declared_size_check.h"

#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

namespace animorph {
namespace {

constexpr char kFbxMagic[] = "Kaydara FBX Binary  ";  // then \0 0x1a 0x00, then a u32 version
constexpr size_t kFbxHeaderBytes = 27;

size_t budgetFor(size_t fileBytes) { return kImportDecodeFactor * fileBytes + kImportDecodeAllowance; }

std::string budgetText(size_t fileBytes) {
  return "the decoding budget of " + std::to_string(budgetFor(fileBytes)) + " bytes (" +
         std::to_string(kImportDecodeFactor) + " x the file's " + std::to_string(fileBytes) + " bytes + " +
         std::to_string(kImportDecodeAllowance >> 20) + " MiB)";
}

// Little-endian reads, bounds-checked by the caller.
uint64_t readLe(const std::string& b, size_t at, size_t width) {
  uint64_t v = 0;
  for (size_t i = 0; i < width; ++i) v |= uint64_t(static_cast<unsigned char>(b[at + i])) << (8 * i);
  return v;
}

struct FbxWalk {
  const std::string& file;
  const std::string& b;
  size_t decoded = 0;  // bytes all arrays together decode to

  Error fail(size_t at, const std::string& record, const std::string& reason) const {
    return Error{file + ": FBX record '" + record + "' at byte " + std::to_string(at) + ": " + reason};
  }
};

// One property at p (advanced past it); arrays add their decoded size to w.decoded.
Status fbxProperty(FbxWalk& w, size_t& p, size_t end, size_t recordAt, const std::string& record) {
  const std::string& b = w.b;
  if (p >= end) return w.fail(recordAt, record, "property list runs past the record's end");
  const char type = b[p++];
  auto need = [&](size_t n) { return end - p >= n; };
  switch (type) {
    case 'C': if (!need(1)) break; p += 1; return {};
    case 'Y': if (!need(2)) break; p += 2; return {};
    case 'I': case 'F': if (!need(4)) break; p += 4; return {};
    case 'D': case 'L': if (!need(8)) break; p += 8; return {};
    case 'S': case 'R': {
      if (!need(4)) break;
      const uint64_t len = readLe(b, p, 4);
      p += 4;
      if (!need(len)) break;
      p += len;
      return {};
    }
    case 'f': case 'i': case 'd': case 'l': case 'b': {
      if (!need(12)) break;
      const uint64_t count = readLe(b, p, 4), encoding = readLe(b, p + 4, 4), stored = readLe(b, p + 8, 4);
      p += 12;
      if (!need(stored)) break;
      p += stored;
      const uint64_t stride = (type == 'd' || type == 'l') ? 8 : (type == 'b' ? 1 : 4);
      const uint64_t full = count * stride;
      const std::string what = std::string("array of ") + std::to_string(count) + " '" + type + "' elements (" +
                               std::to_string(full) + " bytes) stored in " + std::to_string(stored) + " bytes";
      if (encoding == 0 && full != stored) return w.fail(recordAt, record, what + ": the sizes differ");
      if (encoding == 1 && full > kZlibMaxExpansion * stored + 64)
        return w.fail(recordAt, record, what + ": more than zlib can expand to");
      if (encoding > 1)
        return w.fail(recordAt, record, "array encoding " + std::to_string(encoding) + " is unknown (0 or 1)");
      w.decoded += full;
      if (w.decoded > budgetFor(b.size()))
        return w.fail(recordAt, record, what + ": the arrays so far decode to " + std::to_string(w.decoded) +
                                            " bytes, more than " + budgetText(b.size()));
      return {};
    }
    default:
      return w.fail(recordAt, record, std::string("unknown property type '") +
                                          (type >= 0x20 && type < 0x7f ? std::string(1, type) : "?") + "'");
  }
  return w.fail(recordAt, record, std::string("property '") + type + "' runs past the record's end");
}

}  // namespace

bool isFbxBinary(const std::string& bytes) {
  return bytes.size() >= sizeof kFbxMagic - 1 && std::memcmp(bytes.data(), kFbxMagic, sizeof kFbxMagic - 1) == 0;
}

Status checkFbxBinaryDeclaredSizes(const std::string& file, const std::string& b) {
  if (!isFbxBinary(b) || b.size() < kFbxHeaderBytes) return Error{file + ": not a binary FBX file (header too short)"};
  const uint64_t version = readLe(b, 23, 4);
  const size_t width = version >= 7500 ? 8 : 4;  // record header fields grew to 64 bits in FBX 7.5
  const size_t headerBytes = 3 * width + 1;
  FbxWalk w{file, b};
  std::vector<size_t> open;  // end offsets of the records we are inside
  size_t p = kFbxHeaderBytes;
  while (p + headerBytes <= b.size()) {
    while (!open.empty() && p >= open.back()) {
      if (p > open.back()) return w.fail(p, "?", "a nested record runs past its parent's end");
      open.pop_back();
    }
    const size_t at = p;
    const uint64_t endOffset = readLe(b, p, width), props = readLe(b, p + width, width),
                   propBytes = readLe(b, p + 2 * width, width);
    const size_t nameLen = static_cast<unsigned char>(b[p + 3 * width]);
    if (endOffset == 0) {  // the null record that closes a list
      if (open.empty()) return {};  // end of the top-level list: the footer follows
      p += headerBytes;
      continue;
    }
    p += headerBytes;
    if (nameLen > b.size() - p) return w.fail(at, "?", "name runs past the end of the file");
    std::string name = b.substr(p, std::min<size_t>(nameLen, 40));
    for (char& ch : name)
      if (ch < 0x20 || ch > 0x7e) ch = '?';  // a broken file's name may be any bytes
    p += nameLen;
    const size_t limit = open.empty() ? b.size() : open.back();
    if (endOffset <= at || endOffset > limit)
      return w.fail(at, name, "ends at byte " + std::to_string(endOffset) + ", outside " +
                                  (open.empty() ? "the file (" + std::to_string(b.size()) + " bytes)"
                                                : "its parent (ends at " + std::to_string(limit) + ")"));
    if (propBytes > endOffset - p) return w.fail(at, name, "its property list runs past its end");
    const size_t propEnd = p + propBytes;
    for (uint64_t i = 0; i < props; ++i)
      if (auto s = fbxProperty(w, p, propEnd, at, name); !s) return s;
    if (p != propEnd) return w.fail(at, name, "its properties do not fill its property list");
    if (p < endOffset) open.push_back(endOffset);  // nested records follow
    else p = endOffset;
  }
  return {};
}

Status checkTextDeclaredCounts(const std::string& file, const std::string& b, bool collada) {
  size_t decoded = 0;
  const std::string key = collada ? "count=\"" : "*";
  for (size_t p = b.find(key); p != std::string::npos; p = b.find(key, p + 1)) {
    size_t q = p + key.size();
    uint64_t count = 0;
    size_t digits = 0;
    while (q < b.size() && b[q] >= '0' && b[q] <= '9' && digits < 20) {
      count = count * 10 + uint64_t(b[q] - '0');
      ++q;
      ++digits;
    }
    if (digits == 0) continue;
    if (!collada) {  // an ASCII FBX array: "*N {"
      while (q < b.size() && (b[q] == ' ' || b[q] == '\t')) ++q;
      if (q >= b.size() || b[q] != '{') continue;
    }
    if (digits >= 20 || count > budgetFor(b.size()) / 8 || (decoded += count * 8) > budgetFor(b.size()))
      return Error{file + ": " + (collada ? "count" : "array") + " at byte " + std::to_string(p) + " declares " +
                   b.substr(p + key.size(), digits) + " elements; the arrays so far need more than " +
                   budgetText(b.size())};
  }
  return {};
}

Status checkColladaIndexLists(const std::string& file, const std::string& b) {
  for (size_t lt = b.find('<'); lt != std::string::npos; lt = b.find('<', lt + 1)) {
    const char name = lt + 2 < b.size() ? b[lt + 1] : '\0';
    if (name != 'p' && name != 'h') continue;
    const char after = b[lt + 2];
    if (after != '>' && after != ' ' && after != '\t' && after != '\r' && after != '\n') continue;
    const size_t gt = b.find('>', lt);
    if (gt == std::string::npos) return {};  // a cut file: the XML parser says so
    if (b[gt - 1] == '/') continue;          // <p/>: empty
    for (size_t q = gt + 1; q < b.size() && b[q] != '<'; ++q) {
      const char ch = b[q];
      if ((ch >= '0' && ch <= '9') || ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n') continue;
      char shown[16];
      if (ch > ' ' && ch < 127)
        std::snprintf(shown, sizeof shown, "'%c'", ch);
      else
        std::snprintf(shown, sizeof shown, "byte 0x%02X", unsigned(static_cast<unsigned char>(ch)));
      return Error{file + ": <" + std::string(1, name) + "> at byte " + std::to_string(lt) + ": " + shown +
                   " at byte " + std::to_string(q) +
                   " is not a digit or white space (an index list holds unsigned integers only)"};
    }
  }
  return {};
}

namespace {

// The unsigned integers of the text between begin and end (the element's content); at most cap
// of them are summed (each capped), so a broken list costs linear time and cannot overflow.
struct IndexList {
  uint64_t entries = 0, sum = 0;
};

IndexList readIndexList(const std::string& b, size_t begin, size_t end) {
  IndexList l;
  size_t q = begin;
  while (q < end) {
    while (q < end && (b[q] < '0' || b[q] > '9')) ++q;
    if (q >= end) break;
    uint64_t v = 0;
    while (q < end && b[q] >= '0' && b[q] <= '9') {
      v = std::min<uint64_t>(v * 10 + uint64_t(b[q] - '0'), uint64_t(1) << 40);
      ++q;
    }
    ++l.entries;
    l.sum = std::min<uint64_t>(l.sum + v, uint64_t(1) << 50);
  }
  return l;
}

// The content range of the first <tag> inside [from, to): {begin, end} or {npos, npos}.
std::pair<size_t, size_t> elementContent(const std::string& b, const std::string& tag, size_t from, size_t to) {
  const size_t lt = b.find("<" + tag + ">", from);
  if (lt == std::string::npos || lt >= to) return {std::string::npos, std::string::npos};
  const size_t begin = lt + tag.size() + 2, end = b.find("</" + tag + ">", begin);
  if (end == std::string::npos || end > to) return {std::string::npos, std::string::npos};
  return {begin, end};
}

// The largest offset="k" of the <input> elements in [from, to), plus one (0 when none).
uint64_t inputStride(const std::string& b, size_t from, size_t to) {
  uint64_t stride = 0;
  for (size_t p = b.find("offset=\"", from); p != std::string::npos && p < to; p = b.find("offset=\"", p + 1)) {
    uint64_t k = 0;
    for (size_t q = p + 8; q < to && b[q] >= '0' && b[q] <= '9' && k < (uint64_t(1) << 20); ++q)
      k = k * 10 + uint64_t(b[q] - '0');
    stride = std::max(stride, k + 1);
  }
  return stride;
}

}  // namespace

Status checkColladaVertexWeights(const std::string& file, const std::string& b) {
  const std::string open = "<vertex_weights", close = "</vertex_weights>";
  for (size_t at = b.find(open); at != std::string::npos; at = b.find(open, at + 1)) {
    const size_t end = b.find(close, at);
    if (end == std::string::npos) return {};  // a cut file: the XML parser says so
    const size_t tagEnd = b.find('>', at);
    const size_t countAt = b.find("count=\"", at);
    if (countAt == std::string::npos || countAt > tagEnd) continue;  // no count: the XML reader refuses it
    const IndexList count = readIndexList(b, countAt + 7, b.find('"', countAt + 7));
    const auto [vcBegin, vcEnd] = elementContent(b, "vcount", tagEnd, end);
    const auto [vBegin, vEnd] = elementContent(b, "v", tagEnd, end);
    const IndexList vcount = vcBegin == std::string::npos ? IndexList{} : readIndexList(b, vcBegin, vcEnd);
    const IndexList v = vBegin == std::string::npos ? IndexList{} : readIndexList(b, vBegin, vEnd);
    const uint64_t stride = inputStride(b, tagEnd, end);
    const std::string where = file + ": <vertex_weights> at byte " + std::to_string(at) + ": ";
    if (vcount.entries != count.sum)
      return Error{where + "count=\"" + std::to_string(count.sum) + "\" but its <vcount> lists " +
                   std::to_string(vcount.entries) + " numbers"};
    if (v.entries != vcount.sum * stride)
      return Error{where + "its <vcount> adds up to " + std::to_string(vcount.sum) + " influences of " +
                   std::to_string(stride) + " indices each, but its <v> lists " + std::to_string(v.entries)};
  }
  return {};
}

namespace {

// The value of attribute name="..." inside the tag [tagBegin, tagEnd), or def when absent.
std::string attribute(const std::string& b, size_t tagBegin, size_t tagEnd, const std::string& name,
                      const std::string& def) {
  const std::string key = " " + name + "=\"";
  const size_t p = b.find(key, tagBegin);
  if (p == std::string::npos || p >= tagEnd) return def;
  const size_t q = b.find('"', p + key.size());
  return q == std::string::npos || q > tagEnd ? def : b.substr(p + key.size(), q - p - key.size());
}

uint64_t attributeNumber(const std::string& b, size_t tagBegin, size_t tagEnd, const std::string& name,
                         uint64_t def) {
  const std::string v = attribute(b, tagBegin, tagEnd, name, "");
  if (v.empty()) return def;
  const IndexList l = readIndexList(v, 0, v.size());
  return l.entries == 1 ? l.sum : def;
}

// The count="N" of the element whose id is id, or -1 when the file has none.
int64_t arrayCount(const std::string& b, const std::string& id) {
  const size_t p = b.find(" id=\"" + id + "\"");
  if (p == std::string::npos) return -1;
  const size_t lt = b.rfind('<', p), gt = b.find('>', p);
  if (lt == std::string::npos || gt == std::string::npos) return -1;
  return int64_t(attributeNumber(b, lt, gt, "count", 0));
}

}  // namespace

Status checkColladaAccessors(const std::string& file, const std::string& b) {
  const std::string open = "<accessor", close = "</accessor>";
  for (size_t at = b.find(open); at != std::string::npos; at = b.find(open, at + 1)) {
    const size_t tagEnd = b.find('>', at), end = b.find(close, at);
    if (tagEnd == std::string::npos || end == std::string::npos) return {};  // cut: the XML parser says so
    const std::string where = file + ": <accessor> at byte " + std::to_string(at) + ": ";
    const uint64_t count = attributeNumber(b, at, tagEnd, "count", 0),
                   stride = attributeNumber(b, at, tagEnd, "stride", 1),
                   offset = attributeNumber(b, at, tagEnd, "offset", 0);
    uint64_t params = 0;
    for (size_t lt = b.find('<', tagEnd); lt < end; lt = b.find('<', lt + 1)) {
      if (b.compare(lt, 6, "<param") == 0 && (b[lt + 6] == ' ' || b[lt + 6] == '>' || b[lt + 6] == '/')) {
        ++params;
      } else if (b.compare(lt, 7, "</param") != 0 && b.compare(lt, 4, "<!--") != 0) {
        std::string shown = b.substr(lt + 1, std::min<size_t>(12, end - lt - 1));
        for (char& ch : shown)
          if (ch < 0x20 || ch > 0x7e) ch = '?';  // a broken file's element name may be any bytes
        return Error{where + "holds <" + shown + "...>, not a <param>"};
      }
    }
    if (params > stride)
      return Error{where + std::to_string(params) + " <param>s in a stride of " + std::to_string(stride)};
    const std::string source = attribute(b, at, tagEnd, "source", "");
    if (source.size() < 2 || source[0] != '#') continue;  // an external or missing source: assimp refuses it
    const int64_t values = arrayCount(b, source.substr(1));
    if (values >= 0 && double(offset) + double(count) * double(stride) > double(values))  // no overflow
      return Error{where + "reads " + std::to_string(count) + " x " + std::to_string(stride) + " values from " +
                   std::to_string(offset) + " in '" + source.substr(1) + "', which holds " + std::to_string(values)};
  }
  return {};
}

}  // namespace animorph
