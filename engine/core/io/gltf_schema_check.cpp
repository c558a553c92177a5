#include "core/io/gltf_schema_check.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <nlohmann/json.hpp>

#include "core/util/json_text.h"

namespace animorph {
namespace {

using json = nlohmann::json;

const char* kindOf(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "object";
    case json::value_t::array: return "array";
    case json::value_t::string: return "string";
    case json::value_t::boolean: return "boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "integer";
    case json::value_t::number_float: return "number";
    default: return "unknown";
  }
}

// Index: an index into a glTF array or an enum (tinygltf keeps them in an int).
// Size: a byte offset, length, stride or element count (a glTF file and its
// buffers are below 4 GiB, so nothing larger can be backed by data).
enum class Kind { Index, Size, Number, String, Object, Array, NumberArray, IndexArray, ObjectArray };

constexpr long long kMaxIndex = 2147483647LL;
constexpr long long kMaxSize = 4294967295LL;

// The kind each element of an array kind must have.
Kind elementKind(Kind k) {
  switch (k) {
    case Kind::NumberArray: return Kind::Number;
    case Kind::IndexArray: return Kind::Index;
    case Kind::ObjectArray: return Kind::Object;
    default: return k;
  }
}

const char* expected(Kind k) {
  switch (k) {
    case Kind::Index: return "a non-negative integer index";
    case Kind::Size: return "a non-negative integer";
    case Kind::Number: return "a number";
    case Kind::String: return "a string";
    case Kind::Object: return "an object";
    case Kind::Array: return "an array";
    case Kind::NumberArray: return "an array of numbers";
    case Kind::IndexArray: return "an array of non-negative integer indices";
    case Kind::ObjectArray: return "an array of objects";
  }
  return "";
}

// Empty when j has kind k; otherwise "PATH: expected ..., found ..." naming
// the offending element of an array ("nodes[2].children[1]: ...").
std::string mismatch(const json& j, Kind k, const std::string& path) {
  switch (k) {
    case Kind::Index:
    case Kind::Size: {
      if (!j.is_number_integer()) return path + ": expected " + expected(k) + ", found " + kindOf(j);
      if (!j.is_number_unsigned() && j.get<long long>() < 0)
        return path + ": expected " + expected(k) + ", found " + std::to_string(j.get<long long>());
      std::string why;
      if (!jsonInteger(j, 0, k == Kind::Index ? kMaxIndex : kMaxSize, why)) return path + ": " + why;
      return {};
    }
    case Kind::Number: return j.is_number() ? "" : path + ": expected a number, found " + kindOf(j);
    case Kind::String: return j.is_string() ? "" : path + ": expected a string, found " + kindOf(j);
    case Kind::Object: return j.is_object() ? "" : path + ": expected an object, found " + kindOf(j);
    case Kind::Array: return j.is_array() ? "" : path + ": expected an array, found " + kindOf(j);
    case Kind::NumberArray:
    case Kind::IndexArray:
    case Kind::ObjectArray:
      if (!j.is_array()) return path + ": expected " + expected(k) + ", found " + kindOf(j);
      for (size_t i = 0; i < j.size(); ++i)
        if (std::string m = mismatch(j[i], elementKind(k), path + "[" + std::to_string(i) + "]"); !m.empty()) return m;
      return {};
  }
  return {};
}

class Checker {
 public:
  Checker(std::string file, std::vector<std::string>& warnings) : file_(std::move(file)), warnings_(warnings) {}

  // Checks j[key] (if present) has kind k; severe problems become the error.
  void prop(const json& j, const char* key, const std::string& where, Kind k, bool severe) {
    if (!j.is_object() || !j.contains(key)) return;
    const std::string msg = mismatch(j[key], k, where + (where.empty() ? "" : ".") + key);
    if (msg.empty()) return;
    if (severe) {
      fail(msg);
    } else {
      warnings_.push_back(msg + "; ignored");
    }
  }
  // j[key] must be present (tinygltf refuses the file otherwise, with a
  // message that does not say where).
  void need(const json& j, const char* key, const std::string& where) {
    if (j.is_object() && !j.contains(key)) fail(where + (where.empty() ? "" : ".") + key + ": missing (required)");
  }
  void fail(const std::string& msg) {
    if (error_.empty()) error_ = file_ + ": " + msg;
  }
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  std::string file_;
  std::string error_;
  std::vector<std::string>& warnings_;
};

void checkTextureInfo(Checker& c, const json& mat, const char* key, const std::string& where) {
  c.prop(mat, key, where, Kind::Object, false);
  if (!mat.contains(key) || !mat[key].is_object()) return;
  const json& t = mat[key];
  const std::string w = where + "." + key;
  c.prop(t, "index", w, Kind::Index, false);
  c.prop(t, "texCoord", w, Kind::Index, false);
  c.prop(t, "scale", w, Kind::Number, false);
  c.prop(t, "strength", w, Kind::Number, false);
  c.prop(t, "extensions", w, Kind::Object, false);
  if (t.contains("extensions") && t["extensions"].is_object())
    for (const auto& [name, ext] : t["extensions"].items())
      c.prop(t["extensions"], name.c_str(), w + ".extensions", Kind::Object, false);
}

// What the binary chunk of a GLB holds (for buffers without a uri).
struct GlbInfo {
  bool binary = false;
  bool hasBin = false;
  size_t binSize = 0;
};

// The data: URI prefixes tinygltf decodes; any other "data:" URI would be
// taken for a file name.
const char* const kDataUriPrefixes[] = {
    "data:application/octet-stream;base64,", "data:application/gltf-buffer;base64,", "data:image/jpeg;base64,",
    "data:image/png;base64,", "data:image/bmp;base64,", "data:image/gif;base64,", "data:text/plain;base64,"};

bool isBase64Char(char ch) {
  return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '+' || ch == '/';
}

// A buffer's source: its uri, or the GLB's BIN chunk, holding byteLength bytes.
void checkBuffer(Checker& c, const json& b, const std::string& w, const GlbInfo& glb, size_t index) {
  c.need(b, "byteLength", w);
  if (c.failed() || !b["byteLength"].is_number_unsigned()) return;
  const auto byteLength = b["byteLength"].get<unsigned long long>();
  if (!b.contains("uri")) {
    if (!glb.binary) c.fail(w + ".uri: missing (a .gltf buffer needs a file name or a data: URI)");
    else if (index != 0 || !glb.hasBin) c.fail(w + ": no uri, and only buffer 0 of a GLB can use its BIN chunk" + (glb.hasBin ? "" : " (this GLB has none)"));
    else if (byteLength > glb.binSize)
      c.fail(w + ".byteLength: " + std::to_string(byteLength) + " is more than the GLB's BIN chunk (" +
             std::to_string(glb.binSize) + " bytes)");
    return;
  }
  if (!b["uri"].is_string()) return;
  const std::string& uri = b["uri"].get_ref<const std::string&>();
  if (uri.rfind("data:", 0) != 0) return;
  const char* prefix = nullptr;
  for (const char* p : kDataUriPrefixes)
    if (uri.rfind(p, 0) == 0) prefix = p;
  if (!prefix) {
    c.fail(w + ".uri: a data: URI must be base64 with a known type (data:application/octet-stream;base64,...)");
    return;
  }
  // Decoded as tinygltf does: up to the first '=' or invalid character.
  size_t start = std::strlen(prefix), n = 0;
  while (start + n < uri.size() && isBase64Char(uri[start + n])) ++n;
  if (start + n < uri.size() && uri[start + n] != '=') {
    c.fail(w + ".uri: data: URI has a character that is not base64 at offset " + std::to_string(start + n));
    return;
  }
  const size_t decoded = n / 4 * 3 + (n % 4 ? n % 4 - 1 : 0);
  if (decoded != byteLength)
    c.fail(w + ".uri: the data: URI holds " + std::to_string(decoded) + " bytes but byteLength is " +
           std::to_string(byteLength));
}

// Properties tinygltf requires (it refuses the file without them) and enums
// it checks, reported with the element.
void checkRequired(Checker& c, const json& root, const GlbInfo& glb) {
  c.need(root, "asset", "");
  if (root.contains("asset") && root["asset"].is_object()) c.need(root["asset"], "version", "asset");
  auto each = [&](const char* key, auto&& fn) {
    if (!root.contains(key)) return;
    for (size_t i = 0; i < root[key].size() && !c.failed(); ++i)
      fn(root[key][i], std::string(key) + "[" + std::to_string(i) + "]", i);
  };
  each("buffers", [&](const json& b, const std::string& w, size_t i) { checkBuffer(c, b, w, glb, i); });
  each("bufferViews", [&](const json& v, const std::string& w, size_t) {
    for (const char* k : {"buffer", "byteLength"}) c.need(v, k, w);
  });
  each("accessors", [&](const json& a, const std::string& w, size_t) {
    for (const char* k : {"componentType", "count", "type"}) c.need(a, k, w);
    if (c.failed()) return;
    static const char* kTypes[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    const std::string& type = a["type"].get_ref<const std::string&>();
    if (std::none_of(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return type == t; }))
      c.fail(w + ".type: '" + type + "' is not SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
    const auto ct = a["componentType"].get<long long>();
    if (ct < 5120 || ct > 5126)
      c.fail(w + ".componentType: " + std::to_string(ct) + " is not a glTF component type (5120..5126)");
    if (!a.contains("sparse")) return;
    const json& sp = a["sparse"];
    for (const char* k : {"count", "indices", "values"}) c.need(sp, k, w + ".sparse");
    if (c.failed()) return;
    for (const char* k : {"bufferView", "componentType"}) c.need(sp["indices"], k, w + ".sparse.indices");
    c.need(sp["values"], "bufferView", w + ".sparse.values");
  });
  each("meshes", [&](const json& m, const std::string& w, size_t) {
    c.need(m, "primitives", w);
    if (c.failed()) return;
    for (size_t p = 0; p < m["primitives"].size(); ++p)
      c.need(m["primitives"][p], "attributes", w + ".primitives[" + std::to_string(p) + "]");
  });
  each("skins", [&](const json& s, const std::string& w, size_t) { c.need(s, "joints", w); });
  each("animations", [&](const json& a, const std::string& w, size_t) {
    for (const char* k : {"channels", "samplers"}) c.need(a, k, w);
    if (c.failed()) return;
    for (size_t k = 0; k < a["channels"].size() && !c.failed(); ++k) {
      const json& ch = a["channels"][k];
      const std::string cw = w + ".channels[" + std::to_string(k) + "]";
      for (const char* key : {"sampler", "target"}) c.need(ch, key, cw);
      if (c.failed()) return;
      c.need(ch["target"], "path", cw + ".target");
    }
    for (size_t k = 0; k < a["samplers"].size(); ++k)
      for (const char* key : {"input", "output"}) c.need(a["samplers"][k], key, w + ".samplers[" + std::to_string(k) + "]");
  });
}

void checkModel(Checker& c, const json& root) {
  static const char* kArrays[] = {"scenes", "nodes", "meshes", "accessors", "bufferViews", "buffers", "skins",
                                  "animations", "materials", "textures", "images", "samplers", "cameras"};
  c.prop(root, "asset", "", Kind::Object, true);
  c.prop(root, "scene", "", Kind::Index, true);
  c.prop(root, "extensionsUsed", "", Kind::Array, false);
  c.prop(root, "extensionsRequired", "", Kind::Array, true);
  for (const char* a : kArrays) c.prop(root, a, "", Kind::ObjectArray, true);
  if (c.failed()) return;
  auto each = [&](const char* key, auto&& fn) {
    if (!root.contains(key)) return;
    for (size_t i = 0; i < root[key].size(); ++i) {
      const std::string where = std::string(key) + "[" + std::to_string(i) + "]";
      c.prop(root[key][i], "name", where, Kind::String, false);
      fn(root[key][i], where);
    }
  };
  each("scenes", [&](const json& s, const std::string& w) { c.prop(s, "nodes", w, Kind::IndexArray, true); });
  each("nodes", [&](const json& n, const std::string& w) {
    for (const char* k : {"mesh", "skin", "camera"}) c.prop(n, k, w, Kind::Index, true);
    c.prop(n, "children", w, Kind::IndexArray, true);
    for (const char* k : {"matrix", "translation", "rotation", "scale", "weights"}) c.prop(n, k, w, Kind::NumberArray, true);
  });
  each("meshes", [&](const json& m, const std::string& w) {
    c.prop(m, "primitives", w, Kind::ObjectArray, true);
    if (!m.contains("primitives") || !m["primitives"].is_array()) return;
    for (size_t p = 0; p < m["primitives"].size(); ++p) {
      const json& prim = m["primitives"][p];
      const std::string pw = w + ".primitives[" + std::to_string(p) + "]";
      c.prop(prim, "attributes", pw, Kind::Object, true);
      for (const char* k : {"indices", "mode"}) c.prop(prim, k, pw, Kind::Index, true);
      c.prop(prim, "material", pw, Kind::Index, false);
      if (prim.contains("attributes") && prim["attributes"].is_object())
        for (const auto& [name, acc] : prim["attributes"].items())
          c.prop(prim["attributes"], name.c_str(), pw + ".attributes", Kind::Index, true);
    }
  });
  each("accessors", [&](const json& a, const std::string& w) {
    for (const char* k : {"bufferView", "componentType"}) c.prop(a, k, w, Kind::Index, true);
    for (const char* k : {"byteOffset", "count"}) c.prop(a, k, w, Kind::Size, true);
    c.prop(a, "type", w, Kind::String, true);
    c.prop(a, "sparse", w, Kind::Object, true);
    if (!a.contains("sparse") || !a["sparse"].is_object()) return;
    const json& sp = a["sparse"];
    const std::string sw = w + ".sparse";
    // tinygltf keeps a sparse accessor's count and offsets in an int.
    c.prop(sp, "count", sw, Kind::Index, true);
    for (const char* part : {"indices", "values"}) {
      c.prop(sp, part, sw, Kind::Object, true);
      if (!sp.contains(part) || !sp[part].is_object()) continue;
      const std::string pw = sw + "." + part;
      for (const char* k : {"bufferView", "componentType", "byteOffset"}) c.prop(sp[part], k, pw, Kind::Index, true);
    }
  });
  each("bufferViews", [&](const json& b, const std::string& w) {
    c.prop(b, "buffer", w, Kind::Index, true);
    for (const char* k : {"byteOffset", "byteLength", "byteStride"}) c.prop(b, k, w, Kind::Size, true);
  });
  each("buffers", [&](const json& b, const std::string& w) {
    c.prop(b, "byteLength", w, Kind::Size, true);
    c.prop(b, "uri", w, Kind::String, true);
  });
  each("skins", [&](const json& s, const std::string& w) {
    c.prop(s, "joints", w, Kind::IndexArray, true);
    for (const char* k : {"inverseBindMatrices", "skeleton"}) c.prop(s, k, w, Kind::Index, true);
  });
  each("animations", [&](const json& a, const std::string& w) {
    c.prop(a, "channels", w, Kind::ObjectArray, true);
    c.prop(a, "samplers", w, Kind::ObjectArray, true);
    if (c.failed()) return;
    if (a.contains("channels"))
      for (size_t k = 0; k < a["channels"].size(); ++k) {
        const json& ch = a["channels"][k];
        const std::string cw = w + ".channels[" + std::to_string(k) + "]";
        c.prop(ch, "sampler", cw, Kind::Index, true);
        c.prop(ch, "target", cw, Kind::Object, true);
        if (ch.contains("target") && ch["target"].is_object()) c.prop(ch["target"], "node", cw + ".target", Kind::Index, true);
      }
    if (a.contains("samplers"))
      for (size_t k = 0; k < a["samplers"].size(); ++k)
        for (const char* key : {"input", "output"})
          c.prop(a["samplers"][k], key, w + ".samplers[" + std::to_string(k) + "]", Kind::Index, true);
  });
  each("materials", [&](const json& m, const std::string& w) {
    c.prop(m, "pbrMetallicRoughness", w, Kind::Object, false);
    for (const char* k : {"normalTexture", "occlusionTexture", "emissiveTexture"}) checkTextureInfo(c, m, k, w);
    if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object()) {
      const json& pbr = m["pbrMetallicRoughness"];
      const std::string pw = w + ".pbrMetallicRoughness";
      c.prop(pbr, "baseColorFactor", pw, Kind::NumberArray, false);
      c.prop(pbr, "metallicFactor", pw, Kind::Number, false);
      c.prop(pbr, "roughnessFactor", pw, Kind::Number, false);
      for (const char* k : {"baseColorTexture", "metallicRoughnessTexture"}) checkTextureInfo(c, pbr, k, pw);
    }
  });
  each("textures", [&](const json& t, const std::string& w) {
    for (const char* k : {"source", "sampler"}) c.prop(t, k, w, Kind::Index, false);
  });
}

}  // namespace

namespace {

uint32_t readU32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

// The GLB layout (the checks tinygltf makes, as element-named errors): the
// JSON chunk's text and what the BIN chunk holds.
Status splitGlb(const std::string& bytes, const std::string& fileName, std::string& text, GlbInfo& glb) {
  auto fail = [&](const std::string& msg) { return Error{fileName + ": " + msg}; };
  const size_t size = bytes.size();
  if (size < 20) return fail("GLB header: file is truncated (" + std::to_string(size) + " bytes, the header needs 20)");
  const uint64_t length = readU32(bytes, 8), jsonLength = readU32(bytes, 12);
  if (length > size)
    return fail("GLB header: declared length " + std::to_string(length) + " exceeds the file (" + std::to_string(size) +
                " bytes)");
  if (bytes.compare(16, 4, "JSON") != 0) return fail("GLB header: first chunk is not JSON");
  if (jsonLength < 1) return fail("GLB JSON chunk: empty");
  const uint64_t jsonEnd = 20 + jsonLength;
  if (jsonEnd > length)
    return fail("GLB JSON chunk: length " + std::to_string(jsonLength) + " exceeds the declared length (" +
                std::to_string(length) + " bytes)");
  glb.binary = true;
  if (jsonEnd < length) {
    if (jsonEnd + 12 > length) return fail("GLB BIN chunk: truncated (its header and data need 12 bytes or more)");
    const uint64_t binLength = readU32(bytes, jsonEnd);
    if (binLength < 4 || binLength % 4 != 0)
      return fail("GLB BIN chunk: length " + std::to_string(binLength) + " is not a positive multiple of 4");
    if (jsonEnd + 8 + binLength > length)
      return fail("GLB BIN chunk: length " + std::to_string(binLength) + " exceeds the declared length (" +
                  std::to_string(length) + " bytes)");
    if (bytes.compare(jsonEnd + 4, 4, std::string("BIN\0", 4)) != 0)
      return fail("GLB second chunk: type is not BIN");
    glb.hasBin = true;
    glb.binSize = binLength;
  }
  text.assign(bytes, 20, jsonLength);
  return {};
}

// Removes the animation channels whose target names no node (and animations left with none);
// true when it removed any, with a warning per animation.
bool dropNodelessChannels(json& root, std::vector<std::string>& warnings) {
  if (!root.contains("animations") || !root["animations"].is_array()) return false;
  bool any = false;
  json& anims = root["animations"];
  for (size_t a = anims.size(); a-- > 0;) {
    json& chans = anims[a]["channels"];
    size_t dropped = 0;
    std::string pointer;
    for (size_t k = chans.size(); k-- > 0;) {
      const json& t = chans[k]["target"];
      if (t.contains("node")) continue;
      if (t.contains("extensions") && t["extensions"].is_object() && t["extensions"].contains("KHR_animation_pointer"))
        pointer = "KHR_animation_pointer";
      chans.erase(k);
      ++dropped;
    }
    if (dropped == 0) continue;
    any = true;
    const std::string w = "animations[" + std::to_string(a) + "]";
    warnings.push_back(w + ": " + std::to_string(dropped) + " channel(s) animate no node" +
                       (pointer.empty() ? "" : " (" + pointer + ")") + " and are ignored" +
                       (chans.empty() ? "; the animation is left out" : ""));
    if (chans.empty()) anims.erase(a);
  }
  if (anims.empty()) root.erase("animations");
  return any;
}

// The same container with other JSON: .gltf text, or a GLB whose JSON chunk is replaced (padded
// with spaces to 4 bytes) and whose BIN chunk follows unchanged.
std::string withJson(const std::string& bytes, bool binary, const json& root) {
  std::string text = root.dump();
  if (!binary) return text;
  while (text.size() % 4 != 0) text += ' ';
  const uint32_t oldJsonLength = readU32(bytes, 12);
  const std::string rest = bytes.substr(20 + size_t(oldJsonLength), size_t(readU32(bytes, 8)) - 20 - oldJsonLength);
  const uint32_t jsonLength = uint32_t(text.size()), total = uint32_t(20 + text.size() + rest.size()), version = 2;
  std::string out(20, '\0');
  std::memcpy(out.data(), "glTF", 4);
  std::memcpy(out.data() + 4, &version, 4);
  std::memcpy(out.data() + 8, &total, 4);
  std::memcpy(out.data() + 12, &jsonLength, 4);
  std::memcpy(out.data() + 16, "JSON", 4);
  return out + text + rest;
}

}  // namespace

Status checkGltfSchema(const std::string& bytes, const std::string& fileName, std::vector<std::string>& warnings,
                       std::string* withoutPointerChannels) {
  std::string text;
  GlbInfo glb;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) {
    if (Status s = splitGlb(bytes, fileName, text, glb); !s) return s;
  } else {
    text = bytes;
  }
  auto parsed = parseJsonText(text, fileName);
  if (!parsed) return Error{parsed.error()};
  const json& root = *parsed;
  if (!root.is_object()) return Error{fileName + ": top level: expected an object, found " + kindOf(root)};
  Checker c(fileName, warnings);
  checkModel(c, root);
  if (!c.failed()) checkRequired(c, root, glb);
  if (c.failed()) return Error{c.error()};
  if (withoutPointerChannels) {
    json copy = root;
    if (dropNodelessChannels(copy, warnings)) *withoutPointerChannels = withJson(bytes, glb.binary, copy);
  }
  return {};
}

}  // namespace animorph
