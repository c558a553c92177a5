#include "io/gltf_schema_check.h"

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "util/json_text.h"

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
      if (error_.empty()) error_ = file_ + ": " + msg;
    } else {
      warnings_.push_back(msg + "; ignored");
    }
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
    c.prop(sp, "count", sw, Kind::Size, true);
    for (const char* part : {"indices", "values"}) {
      c.prop(sp, part, sw, Kind::Object, true);
      if (!sp.contains(part) || !sp[part].is_object()) continue;
      const std::string pw = sw + "." + part;
      for (const char* k : {"bufferView", "componentType"}) c.prop(sp[part], k, pw, Kind::Index, true);
      c.prop(sp[part], "byteOffset", pw, Kind::Size, true);
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

Status checkGltfSchema(const std::string& bytes, const std::string& fileName, std::vector<std::string>& warnings) {
  std::string text;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) {
    uint32_t chunkLength = 0;
    if (bytes.size() < 20) return Error{fileName + ": GLB header: file is truncated"};
    std::memcpy(&chunkLength, bytes.data() + 12, 4);
    if (bytes.compare(16, 4, "JSON") != 0) return Error{fileName + ": GLB header: first chunk is not JSON"};
    if (chunkLength > bytes.size() - 20) return Error{fileName + ": GLB JSON chunk: length exceeds the file"};
    text.assign(bytes, 20, chunkLength);
  } else {
    text = bytes;
  }
  auto parsed = parseJsonText(text, fileName);
  if (!parsed) return Error{parsed.error()};
  const json& root = *parsed;
  if (!root.is_object()) return Error{fileName + ": top level: expected an object, found " + kindOf(root)};
  Checker c(fileName, warnings);
  checkModel(c, root);
  if (c.failed()) return Error{c.error()};
  return {};
}

}  // namespace animorph
