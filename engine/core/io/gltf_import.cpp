// glTF 2.0 import with Debian's tinygltf (the compiled libtinygltf.so, built
// with stb_image and the default file-system callbacks, so no configuration
// macro is defined here). tinygltf parses JSON and loads buffers; every index,
// bound and type is checked here before a byte is read.
#include "core/io/gltf_import.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_access.hpp>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "core/util/atomic_file.h"
#include "core/io/gltf_schema_check.h"
#include "core/io/texture_decode.h"
#include "core/rig/mesh_normals.h"
#include "core/rig/skin_influences.h"

namespace animorph {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// File access: external URIs must stay inside the glTF file's directory.

struct FsGuard {
  std::string baseDir;  // canonical, no trailing slash
  std::string rejectedUri;
  std::string rejectReason;
  std::string missingUri;
  std::string unreadable;  // readFile's error for the first external file that could not be read
};

bool isInside(const fs::path& p, const fs::path& dir) {
  auto d = dir.begin(), q = p.begin();
  for (; d != dir.end(); ++d, ++q)
    if (q == p.end() || *q != *d) return false;
  return true;
}

// tinygltf joins base_dir and the URI, then retries "./URI" (the working
// directory); only the first form is honoured.
bool guardedFileExists(const std::string& path, void* user) {
  auto* g = static_cast<FsGuard*>(user);
  const std::string prefix = g->baseDir + "/";
  if (path.rfind(prefix, 0) != 0) return false;
  std::string uri = path.substr(prefix.size());
  if (uri.empty()) return false;
  if (uri[0] == '/' || uri[0] == '\\' || (uri.size() > 1 && uri[1] == ':')) {
    if (g->rejectedUri.empty()) { g->rejectedUri = uri; g->rejectReason = "absolute paths are not allowed"; }
    return false;
  }
  std::error_code ec;
  fs::path full = fs::weakly_canonical(fs::path(g->baseDir) / uri, ec);
  if (ec || !isInside(full, fs::path(g->baseDir))) {
    if (g->rejectedUri.empty()) {
      g->rejectedUri = uri;
      g->rejectReason = "resolves outside the glTF file's directory";
    }
    return false;
  }
  if (!fs::is_regular_file(full, ec)) {
    if (g->missingUri.empty()) g->missingUri = uri;
    return false;
  }
  return true;
}

std::string identityExpand(const std::string& path, void*) { return path; }

bool guardedReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (!guardedFileExists(path, user)) {
    if (err) *err = "not readable";
    return false;
  }
  // Regular files under the size cap only, read without blocking.
  auto bytes = readFile(path);
  if (!bytes) {
    auto* g = static_cast<FsGuard*>(user);
    if (g->unreadable.empty()) g->unreadable = bytes.error();
    if (err) *err = bytes.error();
    return false;
  }
  out->assign(bytes->begin(), bytes->end());
  return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is disabled during import";
  return false;
}

// Images are decoded later (io/texture_decode.h, bounded, only those a material draws):
// keep the encoded bytes as they are.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// ---------------------------------------------------------------------------
// Import context and error helpers.

template <class T>
using DecodedCache = std::map<int, std::shared_ptr<const std::vector<T>>>;

struct Ctx {
  const std::string& file;  // the path as given, for messages
  const tinygltf::Model& m;
  ImportReport& report;
  size_t budget = 0;            // bytes all decoded accessors together may take
  mutable size_t spent = 0;      // bytes decoded (or copied from the cache) so far
  std::vector<int> uses{};       // how many times each accessor is referenced
  // Accessors referenced more than once, decoded once (as floats or integers).
  mutable DecodedCache<float> floats{};
  mutable DecodedCache<uint32_t> uints{};

  template <class T>
  DecodedCache<T>& cache() const {
    if constexpr (std::is_same_v<T, float>) return floats;
    else return uints;
  }
};

Error err(const Ctx& c, const std::string& element, const std::string& reason) {
  return Error{c.file + ": " + element + ": " + reason};
}

std::string accessorName(int i) { return "accessor " + std::to_string(i); }

std::string meshLabel(const tinygltf::Model& m, int i) {
  const std::string& n = m.meshes[i].name;
  return n.empty() ? "mesh " + std::to_string(i) : "mesh " + std::to_string(i) + " '" + n + "'";
}

std::string nodeLabel(const tinygltf::Model& m, int i) {
  const std::string& n = m.nodes[i].name;
  return n.empty() ? "node " + std::to_string(i) : "node " + std::to_string(i) + " '" + n + "'";
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown type";
  }
}

const char* componentName(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_INT: return "int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    default: return "unknown component type";
  }
}

size_t componentSize(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

// ---------------------------------------------------------------------------
// Accessors: bounds-checked reads into flat float or integer arrays.

struct Span {
  const unsigned char* data = nullptr;  // null: all zeros (no bufferView)
  size_t stride = 0;
};

// A bufferView range [offset, offset + (count-1)*stride + elemSize) checked
// against the view and the view against its buffer.
Result<Span> viewRange(const Ctx& c, const std::string& element, int viewIndex, size_t offset, size_t count,
                       size_t elemSize, bool allowStride) {
  const auto& m = c.m;
  if (viewIndex < 0 || viewIndex >= static_cast<int>(m.bufferViews.size()))
    return err(c, element, "bufferView " + std::to_string(viewIndex) + " does not exist (" +
                               std::to_string(m.bufferViews.size()) + " bufferViews)");
  const auto& bv = m.bufferViews[viewIndex];
  const std::string bvName = "bufferView " + std::to_string(viewIndex);
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(m.buffers.size()))
    return err(c, bvName, "buffer " + std::to_string(bv.buffer) + " does not exist");
  const auto& buf = m.buffers[bv.buffer];
  if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
    return err(c, bvName, "bytes " + std::to_string(bv.byteOffset) + ".." + std::to_string(bv.byteOffset + bv.byteLength) +
                              " exceed buffer " + std::to_string(bv.buffer) + " (" + std::to_string(buf.data.size()) +
                              " bytes)");
  size_t stride = allowStride && bv.byteStride ? bv.byteStride : elemSize;
  if (stride < elemSize)
    return err(c, element, "byteStride " + std::to_string(stride) + " is smaller than an element (" +
                               std::to_string(elemSize) + " bytes)");
  if (count > 0) {
    // (count-1)*stride + elemSize + offset <= byteLength, without overflow.
    size_t avail = bv.byteLength;
    bool fits = offset <= avail && elemSize <= avail - offset &&
                (count - 1) <= (avail - offset - elemSize) / stride;
    if (!fits)
      return err(c, element, std::to_string(count) + " elements of " + std::to_string(elemSize) + " bytes at offset " +
                                 std::to_string(offset) + " exceed " + bvName + " (" + std::to_string(bv.byteLength) +
                                 " bytes)");
  }
  return Span{buf.data.data() + bv.byteOffset + offset, stride};
}

double readComponent(const unsigned char* p, int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      auto v = static_cast<int8_t>(p[0]);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v; std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v; std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    case TINYGLTF_COMPONENT_TYPE_INT: { int32_t v; std::memcpy(&v, p, 4); return v; }
    default: return 0.0;
  }
}

struct AccessorSpec {
  std::vector<int> types;           // allowed TINYGLTF_TYPE_*
  std::vector<int> componentTypes;  // allowed component types
  const char* usage;                // for messages: "POSITION", "indices", ...
};

// Reads accessor `index` into out (components per element times count).
// T is float or uint32_t. Sparse accessors are applied.
template <class T>
Result<size_t> readAccessor(const Ctx& c, int index, const AccessorSpec& spec, std::vector<T>& out, int& comps) {
  const auto& m = c.m;
  const std::string name = accessorName(index);
  if (index < 0 || index >= static_cast<int>(m.accessors.size()))
    return Error{c.file + ": " + spec.usage + " refers to accessor " + std::to_string(index) + ", which does not exist (" +
                 std::to_string(m.accessors.size()) + " accessors)"};
  const auto& a = m.accessors[index];
  if (std::find(spec.types.begin(), spec.types.end(), a.type) == spec.types.end()) {
    std::string expected;
    for (int t : spec.types) expected += (expected.empty() ? "" : " or ") + std::string(typeName(t));
    return err(c, name, std::string("type ") + typeName(a.type) + " is wrong for " + spec.usage + " (expected " +
                            expected + ")");
  }
  if (std::find(spec.componentTypes.begin(), spec.componentTypes.end(), a.componentType) == spec.componentTypes.end()) {
    std::string expected;
    for (int t : spec.componentTypes) expected += (expected.empty() ? "" : " or ") + std::string(componentName(t));
    return err(c, name, std::string("component type ") + componentName(a.componentType) + " (" +
                            std::to_string(a.componentType) + ") is wrong for " + spec.usage + " (expected " + expected +
                            ")");
  }
  comps = componentCount(a.type);
  const size_t cs = componentSize(a.componentType);
  // Matrix columns of 1- and 2-byte components are padded to 4 bytes; only
  // float matrices are accepted here, so elements are tightly packed.
  const size_t elemSize = cs * comps;
  const size_t count = a.count;
  // Bounds are checked before anything is allocated, so a huge count in a
  // small file cannot exhaust memory; accessors without a bufferView (all
  // zeros, possibly sparse) are held to the decoding budget, as is all else.
  Span span;
  if (a.bufferView >= 0) {
    auto checked = viewRange(c, name, a.bufferView, a.byteOffset, count, elemSize, true);
    if (!checked) return Error{checked.error()};
    span = *checked;
  }
  // count <= 2^32 (schema check) and comps <= 16, so this cannot overflow.
  const size_t bytes = a.count * static_cast<size_t>(comps) * sizeof(T);
  if (bytes > c.budget - c.spent)
    return err(c, name, std::to_string(a.count) + " elements" + (a.bufferView < 0 ? " without a bufferView" : "") +
                            " would decode to " + std::to_string(bytes) + " bytes, more than the " +
                            std::to_string(c.budget - c.spent) + " left of this file's decoding budget (" +
                            std::to_string(kGltfDecodeFactor) + " x the input's " +
                            std::to_string((c.budget - kGltfDecodeAllowance) / kGltfDecodeFactor) + " bytes + " +
                            std::to_string(kGltfDecodeAllowance >> 20) + " MiB)");
  c.spent += bytes;
  auto& cache = c.cache<T>();
  if (auto hit = cache.find(index); hit != cache.end()) {
    out = *hit->second;
    return a.count;
  }
  out.assign(count * comps, T(0));
  if (span.data && count > 0) {  // count 0: out.data() may be null, which memcpy must not get
    const unsigned char* base = span.data;
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && std::is_same_v<T, float> && span.stride == elemSize) {
      std::memcpy(out.data(), base, count * elemSize);
    } else {
      for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < comps; ++k)
          out[i * comps + k] = static_cast<T>(readComponent(base + i * span.stride + k * cs, a.componentType, a.normalized));
    }
  }
  if (a.sparse.isSparse) {
    const size_t n = static_cast<size_t>(std::max(0, a.sparse.count));
    const int ict = a.sparse.indices.componentType;
    if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      return err(c, name, std::string("sparse indices have component type ") + componentName(ict));
    auto idx = viewRange(c, name + " sparse indices", a.sparse.indices.bufferView,
                         static_cast<size_t>(std::max(0, a.sparse.indices.byteOffset)), n, componentSize(ict), false);
    if (!idx) return Error{idx.error()};
    auto val = viewRange(c, name + " sparse values", a.sparse.values.bufferView,
                         static_cast<size_t>(std::max(0, a.sparse.values.byteOffset)), n, elemSize, false);
    if (!val) return Error{val.error()};
    for (size_t i = 0; i < n; ++i) {
      auto target = static_cast<size_t>(readComponent(idx->data + i * componentSize(ict), ict, false));
      if (target >= count)
        return err(c, name, "sparse index " + std::to_string(target) + " out of range (" + std::to_string(count) +
                                " elements)");
      for (int k = 0; k < comps; ++k)
        out[target * comps + k] =
            static_cast<T>(readComponent(val->data + i * elemSize + k * cs, a.componentType, a.normalized));
    }
  }
  if (c.uses[index] > 1) cache.emplace(index, std::make_shared<const std::vector<T>>(out));
  return count;
}

const std::vector<int> kFloatOnly = {TINYGLTF_COMPONENT_TYPE_FLOAT};
const std::vector<int> kFloatOrNormalised = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
const std::vector<int> kRotationTypes = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
const std::vector<int> kIndexTypes = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT};
const std::vector<int> kJointTypes = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};

Status checkFinite(const Ctx& c, int accessor, const std::vector<float>& v, int comps, const char* what) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      return err(c, accessorName(accessor), std::string(what) + " " + std::to_string(i / comps) + " is not finite (" +
                                                (std::isnan(v[i]) ? "NaN" : "Inf") + ")");
  return {};
}

// ---------------------------------------------------------------------------
// Meshes.

struct PrimitiveGeometry {
  std::vector<glm::vec3> positions, normals;
  std::vector<uint32_t> indices;
  std::vector<std::vector<Influence>> influences;  // empty when the primitive has no JOINTS_0
  std::vector<glm::vec4> colors;                   // COLOR_0; empty when the primitive has none
  std::vector<glm::vec2> texcoords;                // the base colour texture's TEXCOORD_n, transformed; empty: none
  // Morph targets: POSITION deltas of each target (one per vertex), NORMAL deltas (empty: none).
  std::vector<std::vector<glm::vec3>> targetPositions, targetNormals;
  bool computedNormals = false;
};

// Triangle list from the primitive's mode; returns false for non-triangle modes.
bool toTriangles(int mode, std::vector<uint32_t>& idx) {
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    idx.resize(idx.size() - idx.size() % 3);
    return true;
  }
  std::vector<uint32_t> tris;
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < idx.size(); ++i) {
      // Alternate the winding so every triangle keeps the strip's orientation.
      if (i % 2 == 0) tris.insert(tris.end(), {idx[i], idx[i + 1], idx[i + 2]});
      else tris.insert(tris.end(), {idx[i + 1], idx[i], idx[i + 2]});
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 1; i + 1 < idx.size(); ++i) tris.insert(tris.end(), {idx[0], idx[i], idx[i + 1]});
  } else {
    return false;
  }
  idx.swap(tris);
  return true;
}

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    default: return "unknown mode";
  }
}

// One VEC3 float attribute of morph target t with vcount elements, or an error naming it.
Status readTargetAttribute(const Ctx& c, int acc, const std::string& label, const char* what, size_t vcount,
                           std::vector<glm::vec3>& out) {
  std::vector<float> raw;
  int comps = 0;
  auto k = readAccessor(c, acc, {{TINYGLTF_TYPE_VEC3}, kFloatOnly, what}, raw, comps);
  if (!k) return Error{k.error()};
  if (*k != vcount)
    return err(c, label, std::string(what) + " has " + std::to_string(*k) + " elements but POSITION has " +
                             std::to_string(vcount));
  if (auto s = checkFinite(c, acc, raw, 3, "delta"); !s) return s;
  out.resize(vcount);
  std::memcpy(out.data(), raw.data(), vcount * sizeof(glm::vec3));
  return {};
}

// The morph targets of a primitive (POSITION and NORMAL deltas; TANGENT deltas are not used).
Status readPrimitiveTargets(const Ctx& c, const tinygltf::Primitive& prim, const std::string& primLabel, size_t vcount,
                            PrimitiveGeometry& g) {
  for (size_t t = 0; t < prim.targets.size(); ++t) {
    const std::string label = primLabel + " morph target " + std::to_string(t);
    auto& pos = g.targetPositions.emplace_back();
    auto& nrm = g.targetNormals.emplace_back();
    const auto& attrs = prim.targets[t];
    for (const auto& [name, acc] : attrs)
      if (name != "POSITION" && name != "NORMAL" && name != "TANGENT")
        return err(c, label, "attribute '" + name + "' cannot be a morph target (POSITION, NORMAL or TANGENT)");
    if (auto it = attrs.find("POSITION"); it != attrs.end()) {
      if (auto s = readTargetAttribute(c, it->second, label, "morph target POSITION", vcount, pos); !s) return s;
    } else {
      pos.assign(vcount, glm::vec3(0.0f));
    }
    if (auto it = attrs.find("NORMAL"); it != attrs.end())
      if (auto s = readTargetAttribute(c, it->second, label, "morph target NORMAL", vcount, nrm); !s) return s;
    if (attrs.count("TANGENT")) c.report.unsupported.push_back("morph target TANGENT deltas (" + label + ")");
  }
  return {};
}

// The base colour texture of a primitive's material: its textureInfo, or null.
const tinygltf::TextureInfo* baseColorTextureInfo(const Ctx& c, const tinygltf::Primitive& prim) {
  if (prim.material < 0 || prim.material >= int(c.m.materials.size())) return nullptr;
  const auto& info = c.m.materials[prim.material].pbrMetallicRoughness.baseColorTexture;
  return info.index >= 0 ? &info : nullptr;
}

// KHR_texture_transform of a textureInfo as a 3x3 matrix (translation * rotation * scale,
// as the extension defines it) and the texCoord set it overrides (or the textureInfo's).
glm::mat3 textureTransform(const tinygltf::TextureInfo& info, int& texCoord) {
  texCoord = info.texCoord;
  auto it = info.extensions.find("KHR_texture_transform");
  if (it == info.extensions.end() || !it->second.IsObject()) return glm::mat3(1.0f);
  const tinygltf::Value& v = it->second;
  auto number = [&](const tinygltf::Value& x, double fallback) {
    return x.IsNumber() ? x.GetNumberAsDouble() : fallback;
  };
  auto pair = [&](const char* key, glm::vec2 fallback) {
    const tinygltf::Value& a = v.Get(key);
    if (!a.IsArray() || a.ArrayLen() != 2) return fallback;
    return glm::vec2(float(number(a.Get(0), fallback.x)), float(number(a.Get(1), fallback.y)));
  };
  const glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
  const float r = float(number(v.Get("rotation"), 0.0));
  if (v.Has("texCoord") && v.Get("texCoord").IsInt()) texCoord = v.Get("texCoord").GetNumberAsInt();
  // T * R * S, column by column as the extension's GLSL writes them (glm is column-major too).
  const glm::mat3 t(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
  const glm::mat3 rot(std::cos(r), std::sin(r), 0, -std::sin(r), std::cos(r), 0, 0, 0, 1);
  const glm::mat3 sc(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return t * rot * sc;
}

// The texture coordinates the primitive's base colour texture uses (TEXCOORD_n of its
// textureInfo, KHR_texture_transform applied). None when the material has no texture or
// the primitive lacks the attribute (a warning: the texture is then drawn at uv (0, 0)).
Status readBaseColorTexcoords(const Ctx& c, const tinygltf::Primitive& prim, const std::string& label, size_t vcount,
                              std::vector<glm::vec2>& out) {
  const tinygltf::TextureInfo* info = baseColorTextureInfo(c, prim);
  if (!info) return Status::success();
  int set = 0;
  const glm::mat3 m = textureTransform(*info, set);
  const std::string attrName = "TEXCOORD_" + std::to_string(set);
  auto it = prim.attributes.find(attrName);
  if (it == prim.attributes.end()) {
    c.report.warnings.push_back(label + ": its material has a base colour texture but the primitive has no " + attrName);
    return Status::success();
  }
  std::vector<float> uv;
  int comps = 0;
  auto k = readAccessor(c, it->second, {{TINYGLTF_TYPE_VEC2}, kFloatOrNormalised, "TEXCOORD"}, uv, comps);
  if (!k) return Error{k.error()};
  if (*k != vcount)
    return err(c, label, attrName + " has " + std::to_string(*k) + " elements but POSITION has " + std::to_string(vcount));
  if (auto s = checkFinite(c, it->second, uv, 2, "texture coordinate"); !s) return Error{s.error()};
  out.resize(vcount);
  for (size_t v = 0; v < vcount; ++v) out[v] = glm::vec2(m * glm::vec3(uv[2 * v], uv[2 * v + 1], 1.0f));
  return Status::success();
}

// Reads one triangle primitive. Returns an empty geometry with a warning for
// recoverable problems.
Result<PrimitiveGeometry> readPrimitive(const Ctx& c, int meshIndex, int primIndex) {
  const auto& prim = c.m.meshes[meshIndex].primitives[primIndex];
  const std::string label = meshLabel(c.m, meshIndex) + " primitive " + std::to_string(primIndex);
  PrimitiveGeometry g;
  auto attr = [&](const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  int posAcc = attr("POSITION");
  if (posAcc < 0) return err(c, label, "no POSITION attribute");
  std::vector<float> pos;
  int comps = 0;
  auto n = readAccessor(c, posAcc, {{TINYGLTF_TYPE_VEC3}, kFloatOnly, "POSITION"}, pos, comps);
  if (!n) return Error{n.error()};
  if (auto s = checkFinite(c, posAcc, pos, 3, "position"); !s) return Error{s.error()};
  const size_t vcount = *n;
  g.positions.resize(vcount);
  std::memcpy(g.positions.data(), pos.data(), vcount * sizeof(glm::vec3));

  // Indices (or 0..n-1), range-checked, then converted to a triangle list.
  if (prim.indices >= 0) {
    int ic = 0;
    auto k = readAccessor(c, prim.indices, {{TINYGLTF_TYPE_SCALAR}, kIndexTypes, "indices"}, g.indices, ic);
    if (!k) return Error{k.error()};
    for (uint32_t i : g.indices)
      if (i >= vcount)
        return err(c, accessorName(prim.indices),
                   "index " + std::to_string(i) + " out of range (" + std::to_string(vcount) + " vertices)");
  } else {
    g.indices.resize(vcount);
    for (size_t i = 0; i < vcount; ++i) g.indices[i] = static_cast<uint32_t>(i);
  }
  if (prim.mode == TINYGLTF_MODE_TRIANGLES && g.indices.size() % 3 != 0)
    c.report.warnings.push_back(label + ": " + std::to_string(g.indices.size()) +
                                (prim.indices >= 0 ? " indices" : " vertices") +
                                " is not a multiple of 3; the last " + std::to_string(g.indices.size() % 3) +
                                " ignored");
  toTriangles(prim.mode, g.indices);

  int nrmAcc = attr("NORMAL");
  if (nrmAcc >= 0) {
    std::vector<float> nrm;
    auto k = readAccessor(c, nrmAcc, {{TINYGLTF_TYPE_VEC3}, kFloatOnly, "NORMAL"}, nrm, comps);
    if (!k) return Error{k.error()};
    if (*k != vcount)
      return err(c, label, "NORMAL has " + std::to_string(*k) + " elements but POSITION has " + std::to_string(vcount));
    if (auto s = checkFinite(c, nrmAcc, nrm, 3, "normal"); !s) return Error{s.error()};
    g.normals.resize(vcount);
    std::memcpy(g.normals.data(), nrm.data(), vcount * sizeof(glm::vec3));
    for (auto& v : g.normals) {
      float len = glm::length(v);
      v = len > 1e-20f ? v / len : glm::vec3(0, 1, 0);
    }
  } else {
    g.normals = computeAreaWeightedNormals(g.positions, g.indices);
    g.computedNormals = true;
  }

  int colAcc = attr("COLOR_0");
  if (colAcc >= 0) {
    std::vector<float> col;
    int cc = 0;
    auto k = readAccessor(c, colAcc, {{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, kFloatOrNormalised, "COLOR_0"}, col, cc);
    if (!k) return Error{k.error()};
    if (*k != vcount)
      return err(c, label, "COLOR_0 has " + std::to_string(*k) + " elements but POSITION has " + std::to_string(vcount));
    if (auto s = checkFinite(c, colAcc, col, cc, "colour"); !s) return Error{s.error()};
    g.colors.resize(vcount);
    for (size_t v = 0; v < vcount; ++v)
      g.colors[v] = glm::clamp(glm::vec4(col[v * cc], col[v * cc + 1], col[v * cc + 2], cc == 4 ? col[v * cc + 3] : 1.0f),
                               0.0f, 1.0f);
  }

  if (auto s = readBaseColorTexcoords(c, prim, label, vcount, g.texcoords); !s) return Error{s.error()};

  // Every JOINTS_n / WEIGHTS_n pair contributes influences.
  for (int set = 0;; ++set) {
    int ja = attr(("JOINTS_" + std::to_string(set)).c_str());
    int wa = attr(("WEIGHTS_" + std::to_string(set)).c_str());
    if (ja < 0 && wa < 0) break;
    if (ja < 0 || wa < 0)
      return err(c, label, "JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set) +
                               " must come together");
    std::vector<uint32_t> joints;
    std::vector<float> weights;
    int jc = 0, wc = 0;
    auto jn = readAccessor(c, ja, {{TINYGLTF_TYPE_VEC4}, kJointTypes, "JOINTS"}, joints, jc);
    if (!jn) return Error{jn.error()};
    auto wn = readAccessor(c, wa, {{TINYGLTF_TYPE_VEC4}, kFloatOrNormalised, "WEIGHTS"}, weights, wc);
    if (!wn) return Error{wn.error()};
    if (*jn != vcount || *wn != vcount)
      return err(c, label, "JOINTS_" + std::to_string(set) + "/WEIGHTS_" + std::to_string(set) + " have " +
                               std::to_string(*jn) + "/" + std::to_string(*wn) + " elements but POSITION has " +
                               std::to_string(vcount));
    if (g.influences.empty()) g.influences.resize(vcount);
    for (size_t v = 0; v < vcount; ++v)
      for (int k = 0; k < 4; ++k)
        if (weights[v * 4 + k] != 0.0f) g.influences[v].push_back({joints[v * 4 + k], weights[v * 4 + k]});
  }
  if (auto s = readPrimitiveTargets(c, prim, label, vcount, g); !s) return Error{s.error()};
  return g;
}

// The primitives' morph targets concatenated as their vertices are (a primitive
// with fewer targets gets zero deltas), their names (mesh.extras.targetNames) and
// the mesh's default weights. The concatenated deltas are charged to the decoding
// budget: a primitive with many targets beside a large one without cannot blow it up.
Status concatenateMorphTargets(const Ctx& c, int meshIndex, const std::vector<PrimitiveGeometry>& prims, Mesh& mesh) {
  const auto& gm = c.m.meshes[meshIndex];
  size_t targets = 0;
  bool anyNormals = false;
  for (const auto& g : prims) {
    if (targets && !g.targetPositions.empty() && g.targetPositions.size() != targets)
      c.report.warnings.push_back(meshLabel(c.m, meshIndex) + ": primitives have different numbers of morph targets (" +
                                  std::to_string(targets) + " and " + std::to_string(g.targetPositions.size()) +
                                  "); missing ones move nothing");
    targets = std::max(targets, g.targetPositions.size());
    for (const auto& n : g.targetNormals) anyNormals |= !n.empty();
  }
  if (targets == 0) {
    if (!gm.weights.empty())
      c.report.warnings.push_back(meshLabel(c.m, meshIndex) + ": has weights but no morph targets; ignored");
    return {};
  }
  const size_t n = mesh.vertexCount();
  const size_t bytes = targets * n * sizeof(glm::vec3) * (anyNormals ? 2 : 1);
  if (bytes > c.budget - c.spent)
    return err(c, meshLabel(c.m, meshIndex), std::to_string(targets) + " morph targets over " + std::to_string(n) +
                                                 " vertices would take " + std::to_string(bytes) +
                                                 " bytes, more than the " + std::to_string(c.budget - c.spent) +
                                                 " left of this file's decoding budget");
  c.spent += bytes;
  mesh.morphTargets.resize(targets);
  const tinygltf::Value* names = gm.extras.Has("targetNames") ? &gm.extras.Get("targetNames") : nullptr;
  for (size_t t = 0; t < targets; ++t) {
    MorphTarget& mt = mesh.morphTargets[t];
    mt.name = "target " + std::to_string(t);
    if (names && names->IsArray() && t < names->ArrayLen() && names->Get(int(t)).IsString())
      mt.name = names->Get(int(t)).Get<std::string>();
    mt.positionDeltas.reserve(n);
    if (anyNormals) mt.normalDeltas.reserve(n);
    for (const auto& g : prims) {
      const size_t pn = g.positions.size();
      const bool has = t < g.targetPositions.size();
      if (has) mt.positionDeltas.insert(mt.positionDeltas.end(), g.targetPositions[t].begin(), g.targetPositions[t].end());
      else mt.positionDeltas.insert(mt.positionDeltas.end(), pn, glm::vec3(0.0f));
      if (!anyNormals) continue;
      if (has && !g.targetNormals[t].empty())
        mt.normalDeltas.insert(mt.normalDeltas.end(), g.targetNormals[t].begin(), g.targetNormals[t].end());
      else mt.normalDeltas.insert(mt.normalDeltas.end(), pn, glm::vec3(0.0f));
    }
  }
  mesh.defaultMorphWeights.assign(targets, 0.0f);
  if (!gm.weights.empty() && gm.weights.size() != targets)
    return err(c, meshLabel(c.m, meshIndex), std::to_string(gm.weights.size()) + " weights for " +
                                                 std::to_string(targets) + " morph targets");
  for (size_t t = 0; t < gm.weights.size(); ++t) {
    if (!std::isfinite(gm.weights[t])) return err(c, meshLabel(c.m, meshIndex), "weight " + std::to_string(t) + " is not finite");
    mesh.defaultMorphWeights[t] = static_cast<float>(gm.weights[t]);
  }
  return {};
}

// A node's own weights (glTF node.weights) replace its mesh's defaults: the
// Character keeps one set per mesh, so nodes that share a mesh with different
// weights get a warning and the first node's weights.
Status applyNodeMorphWeights(const Ctx& c, Character& ch) {
  std::vector<int> setBy(ch.meshes.size(), -1);
  for (size_t i = 0; i < ch.nodes.size(); ++i) {
    const auto& w = c.m.nodes[i].weights;
    const int mi = ch.nodes[i].mesh;
    if (w.empty() || mi < 0) continue;
    Mesh& mesh = ch.meshes[size_t(mi)];
    if (w.size() != mesh.morphTargets.size())
      return err(c, nodeLabel(c.m, int(i)), std::to_string(w.size()) + " weights for the " +
                                                std::to_string(mesh.morphTargets.size()) + " morph targets of its mesh");
    std::vector<float> wf(w.size());
    for (size_t t = 0; t < w.size(); ++t) {
      if (!std::isfinite(w[t])) return err(c, nodeLabel(c.m, int(i)), "weight " + std::to_string(t) + " is not finite");
      wf[t] = static_cast<float>(w[t]);
    }
    if (setBy[size_t(mi)] >= 0) {
      if (wf != mesh.defaultMorphWeights)
        c.report.warnings.push_back(nodeLabel(c.m, int(i)) + ": its weights differ from those of " +
                                    nodeLabel(c.m, setBy[size_t(mi)]) + ", which draws the same mesh; " +
                                    "both show the latter's");
      continue;
    }
    setBy[size_t(mi)] = int(i);
    mesh.defaultMorphWeights = std::move(wf);
  }
  return {};
}

// Concatenates the triangle primitives of mesh meshIndex.
Result<Mesh> readMesh(const Ctx& c, int meshIndex) {
  const auto& gm = c.m.meshes[meshIndex];
  Mesh mesh;
  mesh.name = gm.name.empty() ? "mesh " + std::to_string(meshIndex) : gm.name;
  bool computed = false;
  bool anySkinned = false;
  std::vector<PrimitiveGeometry> prims;
  std::vector<int> materials;  // of each kept primitive
  for (int p = 0; p < static_cast<int>(gm.primitives.size()); ++p) {
    const auto& prim = gm.primitives[p];
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      c.report.unsupported.push_back(std::string(modeName(prim.mode)) + " primitive (" + meshLabel(c.m, meshIndex) +
                                     " primitive " + std::to_string(p) + ", skipped)");
      continue;
    }
    auto g = readPrimitive(c, meshIndex, p);
    if (!g) return Error{g.error()};
    if (mesh.material < 0 && prim.material >= 0 && prim.material < int(c.m.materials.size())) mesh.material = prim.material;
    computed |= g->computedNormals;
    anySkinned |= !g->influences.empty();
    prims.push_back(std::move(*g));
    materials.push_back(prim.material >= 0 && prim.material < int(c.m.materials.size()) ? prim.material : -1);
  }
  InfluenceStats stats;
  bool needSecondSet = false;
  const bool anyColors = std::any_of(prims.begin(), prims.end(), [](const auto& g) { return !g.colors.empty(); });
  const bool anyTexcoords = std::any_of(prims.begin(), prims.end(), [](const auto& g) { return !g.texcoords.empty(); });
  for (size_t p = 0; p < prims.size(); ++p) {
    auto& g = prims[p];
    const uint32_t firstIndex = static_cast<uint32_t>(mesh.indices.size());
    mesh.parts.push_back({firstIndex, static_cast<uint32_t>(g.indices.size()), materials[p]});
    if (anyTexcoords) {  // a primitive without texture coordinates samples uv (0, 0)
      if (g.texcoords.empty()) mesh.texcoords0.insert(mesh.texcoords0.end(), g.positions.size(), glm::vec2(0.0f));
      else mesh.texcoords0.insert(mesh.texcoords0.end(), g.texcoords.begin(), g.texcoords.end());
    }
    if (anyColors) {  // a primitive without COLOR_0 is white, as glTF renders it
      if (g.colors.empty()) mesh.colors.insert(mesh.colors.end(), g.positions.size(), glm::vec4(1.0f));
      else mesh.colors.insert(mesh.colors.end(), g.colors.begin(), g.colors.end());
    }
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), g.positions.begin(), g.positions.end());
    mesh.normals.insert(mesh.normals.end(), g.normals.begin(), g.normals.end());
    for (uint32_t i : g.indices) mesh.indices.push_back(base + i);
    const size_t n = g.positions.size();
    mesh.joints0.resize(base + n, glm::uvec4(0));
    mesh.weights0.resize(base + n, glm::vec4(1, 0, 0, 0));
    mesh.joints1.resize(base + n, glm::uvec4(0));
    mesh.weights1.resize(base + n, glm::vec4(0));
    if (g.influences.empty()) continue;
    for (size_t v = 0; v < n; ++v) {
      packInfluences(g.influences[v], mesh.joints0[base + v], mesh.weights0[base + v], mesh.joints1[base + v],
                     mesh.weights1[base + v], stats);
      needSecondSet |= mesh.weights1[base + v].x > 0.0f;
    }
  }
  if (!needSecondSet) {
    mesh.joints1.clear();
    mesh.weights1.clear();
  }
  c.report.weightsNormalised += stats.normalised;
  c.report.influencesDropped += stats.dropped;
  if (stats.unweighted)
    c.report.warnings.push_back(meshLabel(c.m, meshIndex) + ": " + std::to_string(stats.unweighted) +
                                " vertices have no skin weight; bound to the skin's first joint");
  if (stats.dropped)
    c.report.warnings.push_back(meshLabel(c.m, meshIndex) + ": " + std::to_string(stats.dropped) +
                                " vertices have more than 8 influences; the smallest were dropped");
  if (computed) ++c.report.normalsComputed;
  if (mesh.indices.empty()) c.report.warnings.push_back(meshLabel(c.m, meshIndex) + ": no triangles");
  (void)anySkinned;
  if (auto s = concatenateMorphTargets(c, meshIndex, prims, mesh); !s) return Error{s.error()};
  return mesh;
}

// ---------------------------------------------------------------------------
// Nodes, skins, animations.

Result<Transform> readNodeTransform(const Ctx& c, int i) {
  const auto& n = c.m.nodes[i];
  auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (!finite(n.matrix) || !finite(n.translation) || !finite(n.rotation) || !finite(n.scale))
    return err(c, nodeLabel(c.m, i), "transform is not finite");
  Transform t;
  if (n.matrix.size() == 16) {
    glm::mat4 m;
    for (int k = 0; k < 16; ++k) m[k / 4][k % 4] = static_cast<float>(n.matrix[k]);
    Transform d = decompose(m);
    // A zero axis leaves the rotation undefined (NaN): that axis is hidden anyway.
    if (!std::isfinite(d.rotation.w) || !std::isfinite(d.rotation.x) || !std::isfinite(d.rotation.y) ||
        !std::isfinite(d.rotation.z))
      d.rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    const glm::mat4 back = d.matrix();
    float largest = 1.0f, worst = 0.0f;
    for (int k = 0; k < 16; ++k) {
      largest = std::max(largest, std::abs(m[k / 4][k % 4]));
      worst = std::max(worst, std::abs(back[k / 4][k % 4] - m[k / 4][k % 4]));
    }
    if (worst > 1e-3f * largest)
      c.report.warnings.push_back(nodeLabel(c.m, i) +
                                  ": matrix is not translation x rotation x scale (it has shear or a projection); "
                                  "the nearest such transform is used");
    return d;
  }
  if (!n.matrix.empty()) return err(c, nodeLabel(c.m, i), "matrix has " + std::to_string(n.matrix.size()) + " values");
  if (n.translation.size() == 3) t.translation = {n.translation[0], n.translation[1], n.translation[2]};
  if (n.scale.size() == 3) t.scale = {n.scale[0], n.scale[1], n.scale[2]};
  if (n.rotation.size() == 4) {
    glm::quat q(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]), static_cast<float>(n.rotation[1]),
                static_cast<float>(n.rotation[2]));
    float len = glm::length(q);
    if (len < 1e-6f) return err(c, nodeLabel(c.m, i), "rotation is a zero quaternion");
    t.rotation = q / len;
  }
  return t;
}

Status readHierarchy(const Ctx& c, Character& ch) {
  const auto& m = c.m;
  const int n = static_cast<int>(m.nodes.size());
  ch.nodes.resize(n);
  for (int i = 0; i < n; ++i) {
    const auto& gn = m.nodes[i];
    Node& node = ch.nodes[i];
    node.name = gn.name.empty() ? "node " + std::to_string(i) : gn.name;
    auto t = readNodeTransform(c, i);
    if (!t) return Error{t.error()};
    node.rest = *t;
    if (gn.mesh >= static_cast<int>(m.meshes.size()))
      return err(c, nodeLabel(m, i), "mesh " + std::to_string(gn.mesh) + " does not exist");
    if (gn.skin >= static_cast<int>(m.skins.size()))
      return err(c, nodeLabel(m, i), "skin " + std::to_string(gn.skin) + " does not exist");
    node.mesh = gn.mesh < 0 ? -1 : gn.mesh;
    node.skin = gn.skin < 0 ? -1 : gn.skin;
    for (int child : gn.children) {
      if (child < 0 || child >= n)
        return err(c, nodeLabel(m, i), "child " + std::to_string(child) + " does not exist (" + std::to_string(n) +
                                           " nodes)");
      if (child == i) return err(c, nodeLabel(m, i), "is its own child (cyclic hierarchy)");
      if (ch.nodes[child].parent >= 0 && ch.nodes[child].parent != i)
        return err(c, nodeLabel(m, child), "has two parents (node " + std::to_string(ch.nodes[child].parent) +
                                               " and node " + std::to_string(i) + ")");
      if (ch.nodes[child].parent == i)
        return err(c, nodeLabel(m, i), "lists child " + std::to_string(child) + " twice");
      ch.nodes[child].parent = i;
      node.children.push_back(child);
    }
  }
  // With one parent per node, a cycle is a parent chain that comes back.
  std::vector<char> state(n, 0);  // 0 unknown, 1 on the current walk, 2 reaches a root
  for (int i = 0; i < n; ++i) {
    std::vector<int> walk;
    int k = i;
    while (k >= 0 && state[k] == 0) {
      state[k] = 1;
      walk.push_back(k);
      k = ch.nodes[k].parent;
    }
    if (k >= 0 && state[k] == 1) {
      std::string chain = std::to_string(k);
      for (int p = ch.nodes[k].parent; p != k; p = ch.nodes[p].parent) chain += " -> " + std::to_string(p);
      return err(c, nodeLabel(m, k), "cyclic hierarchy (parent chain " + chain + " -> " + std::to_string(k) + ")");
    }
    for (int w : walk) state[w] = 2;
  }
  // Roots: the default scene's nodes, else every parentless node.
  int scene = m.defaultScene >= 0 ? m.defaultScene : (m.scenes.empty() ? -1 : 0);
  if (scene >= static_cast<int>(m.scenes.size()))
    return err(c, "scene " + std::to_string(scene), "does not exist (" + std::to_string(m.scenes.size()) + " scenes)");
  if (scene >= 0) {
    for (int r : m.scenes[scene].nodes) {
      if (r < 0 || r >= n) return err(c, "scene " + std::to_string(scene), "node " + std::to_string(r) + " does not exist");
      if (ch.nodes[r].parent >= 0)
        c.report.warnings.push_back("scene " + std::to_string(scene) + ": " + nodeLabel(m, r) +
                                    " is listed as a root but has a parent");
      ch.roots.push_back(r);
    }
    if (m.scenes.size() > 1)
      c.report.unsupported.push_back("additional scenes (" + std::to_string(m.scenes.size() - 1) + ", only scene " +
                                     std::to_string(scene) + " is used)");
  } else {
    for (int i = 0; i < n; ++i)
      if (ch.nodes[i].parent < 0) ch.roots.push_back(i);
  }
  return {};
}

Status readSkins(const Ctx& c, Character& ch) {
  const auto& m = c.m;
  for (int s = 0; s < static_cast<int>(m.skins.size()); ++s) {
    const auto& gs = m.skins[s];
    const std::string label = "skin " + std::to_string(s);
    Skin skin;
    skin.name = gs.name.empty() ? label : gs.name;
    if (gs.joints.empty()) return err(c, label, "has no joints");
    for (int j : gs.joints) {
      if (j < 0 || j >= static_cast<int>(ch.nodes.size()))
        return err(c, label, "joint node " + std::to_string(j) + " does not exist");
      skin.joints.push_back(j);
    }
    if (gs.skeleton >= static_cast<int>(ch.nodes.size()))
      return err(c, label, "skeleton node " + std::to_string(gs.skeleton) + " does not exist");
    skin.skeletonRoot = gs.skeleton;
    skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
    if (gs.inverseBindMatrices >= 0) {
      std::vector<float> mats;
      int comps = 0;
      auto k = readAccessor(c, gs.inverseBindMatrices, {{TINYGLTF_TYPE_MAT4}, kFloatOnly, "inverseBindMatrices"}, mats,
                            comps);
      if (!k) return Error{k.error()};
      if (*k < skin.joints.size())
        return err(c, accessorName(gs.inverseBindMatrices),
                   std::to_string(*k) + " inverse bind matrices for " + std::to_string(skin.joints.size()) + " joints");
      if (auto st = checkFinite(c, gs.inverseBindMatrices, mats, 16, "matrix"); !st) return st;
      for (size_t j = 0; j < skin.joints.size(); ++j) {
        glm::mat4& ibm = skin.inverseBindMatrices[j];
        std::memcpy(&ibm[0][0], &mats[j * 16], 16 * sizeof(float));
        const std::string which = label + ": inverse bind matrix " + std::to_string(j) + " (joint node " +
                                  std::to_string(skin.joints[j]) + ")";
        const glm::vec4 lastRow = glm::row(ibm, 3) - glm::vec4(0, 0, 0, 1);
        if (std::max({std::abs(lastRow.x), std::abs(lastRow.y), std::abs(lastRow.z), std::abs(lastRow.w)}) > 1e-5f)
          c.report.warnings.push_back(which + " is not affine (its last row is not 0 0 0 1)");
        else if (std::abs(glm::determinant(glm::mat3(ibm))) < 1e-12f)
          c.report.warnings.push_back(which + " is not invertible; vertices bound to this joint collapse");
      }
    }
    ch.skins.push_back(std::move(skin));
  }
  return {};
}

// The keys of a "weights" channel (out.timesSec already read): one weight per
// morph target of the node's mesh per key (three with CUBICSPLINE), into
// out.weightValues. false (with a warning) when the node draws no mesh with targets.
Result<bool> readWeightKeys(const Ctx& c, const Character& ch, int node, const tinygltf::AnimationSampler& gs,
                            const std::string& chLabel, Channel& out) {
  const int mi = ch.nodes[size_t(node)].mesh;
  const size_t targets = mi < 0 ? 0 : ch.meshes[size_t(mi)].morphTargets.size();
  if (targets == 0) {
    c.report.warnings.push_back(chLabel + ": animates the weights of " + nodeLabel(c.m, node) +
                                ", which draws no mesh with morph targets; skipped");
    return false;
  }
  std::vector<float> vals;
  int comps = 0;
  auto nv = readAccessor(c, gs.output, {{TINYGLTF_TYPE_SCALAR}, kRotationTypes, "animation output (weights)"}, vals, comps);
  if (!nv) return Error{nv.error()};
  const size_t perKey = (out.interpolation == Interpolation::CubicSpline ? 3 : 1) * targets;
  if (*nv != perKey * out.timesSec.size())
    return err(c, accessorName(gs.output), std::to_string(*nv) + " weights for " + std::to_string(out.timesSec.size()) +
                                               " keys of " + std::to_string(targets) + " morph targets (" +
                                               gs.interpolation + " needs " +
                                               std::to_string(perKey * out.timesSec.size()) + ")");
  if (auto st = checkFinite(c, gs.output, vals, 1, "weight"); !st) return Error{st.error()};
  out.weightValues = std::move(vals);
  out.weightCount = static_cast<int>(targets);
  return true;
}

Status readAnimations(const Ctx& c, Character& ch) {
  const auto& m = c.m;
  for (int a = 0; a < static_cast<int>(m.animations.size()); ++a) {
    const auto& ga = m.animations[a];
    const std::string label = "animation " + std::to_string(a) + (ga.name.empty() ? "" : " '" + ga.name + "'");
    AnimationClip clip;
    clip.name = ga.name.empty() ? "animation " + std::to_string(a) : ga.name;
    for (int k = 0; k < static_cast<int>(ga.channels.size()); ++k) {
      const auto& gc = ga.channels[k];
      const std::string chLabel = label + " channel " + std::to_string(k);
      Channel out;
      if (gc.target_path == "translation") out.path = ChannelPath::Translation;
      else if (gc.target_path == "rotation") out.path = ChannelPath::Rotation;
      else if (gc.target_path == "scale") out.path = ChannelPath::Scale;
      else if (gc.target_path == "weights") out.path = ChannelPath::Weights;
      else {
        c.report.unsupported.push_back("animation path '" + gc.target_path + "' (" + label + ")");
        continue;
      }
      if (gc.target_node < 0) {
        c.report.warnings.push_back(chLabel + ": no target node; skipped");
        continue;
      }
      if (gc.target_node >= static_cast<int>(ch.nodes.size()))
        return err(c, chLabel, "target node " + std::to_string(gc.target_node) + " does not exist");
      if (gc.sampler < 0 || gc.sampler >= static_cast<int>(ga.samplers.size()))
        return err(c, chLabel, "sampler " + std::to_string(gc.sampler) + " does not exist");
      const auto& gs = ga.samplers[gc.sampler];
      out.node = gc.target_node;
      if (gs.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
      else if (gs.interpolation == "STEP") out.interpolation = Interpolation::Step;
      else if (gs.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
      else return err(c, label + " sampler " + std::to_string(gc.sampler), "unknown interpolation '" + gs.interpolation + "'");
      int comps = 0;
      auto nt = readAccessor(c, gs.input, {{TINYGLTF_TYPE_SCALAR}, kFloatOnly, "animation input"}, out.timesSec, comps);
      if (!nt) return Error{nt.error()};
      if (*nt == 0) {
        c.report.warnings.push_back(chLabel + ": no keys; skipped");
        continue;
      }
      for (size_t i = 0; i < out.timesSec.size(); ++i) {
        if (!std::isfinite(out.timesSec[i]))
          return err(c, accessorName(gs.input), "key time " + std::to_string(i) + " is not finite");
        if (i > 0 && out.timesSec[i] < out.timesSec[i - 1])
          return err(c, accessorName(gs.input), "key times decrease at key " + std::to_string(i));
      }
      // Accepted, but not what glTF allows: said once per accessor.
      if (out.timesSec.front() < 0.0f)
        c.report.warnings.push_back(accessorName(gs.input) + ": key times start below zero (" +
                                    std::to_string(out.timesSec.front()) + " s)");
      for (size_t i = 1; i < out.timesSec.size(); ++i)
        if (out.timesSec[i] == out.timesSec[i - 1]) {
          c.report.warnings.push_back(accessorName(gs.input) + ": key time " + std::to_string(out.timesSec[i]) +
                                      " s repeats at key " + std::to_string(i));
          break;
        }
      if (out.path == ChannelPath::Weights) {
        auto w = readWeightKeys(c, ch, gc.target_node, gs, chLabel, out);
        if (!w) return Error{w.error()};
        if (!*w) continue;
        clip.durationSec = std::max(clip.durationSec, out.timesSec.back());
        clip.channels.push_back(std::move(out));
        continue;
      }
      const bool rotation = out.path == ChannelPath::Rotation;
      std::vector<float> vals;
      auto nv = readAccessor(c, gs.output,
                             {{rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3},
                              rotation ? kRotationTypes : kFloatOnly, "animation output"},
                             vals, comps);
      if (!nv) return Error{nv.error()};
      const size_t perKey = out.interpolation == Interpolation::CubicSpline ? 3 : 1;
      if (*nv != perKey * *nt)
        return err(c, accessorName(gs.output), std::to_string(*nv) + " values for " + std::to_string(*nt) + " keys (" +
                                                   gs.interpolation + " needs " + std::to_string(perKey * *nt) + ")");
      if (auto st = checkFinite(c, gs.output, vals, comps, "value"); !st) return st;
      out.values.resize(*nv);
      for (size_t i = 0; i < *nv; ++i)
        out.values[i] = rotation ? glm::vec4(vals[i * 4], vals[i * 4 + 1], vals[i * 4 + 2], vals[i * 4 + 3])
                                 : glm::vec4(vals[i * 3], vals[i * 3 + 1], vals[i * 3 + 2], 0.0f);
      clip.durationSec = std::max(clip.durationSec, out.timesSec.back());
      clip.channels.push_back(std::move(out));
    }
    ch.clips.push_back(std::move(clip));
  }
  return {};
}

// Joint indices must address the skin the mesh is drawn with; a mesh with
// joints drawn without a skin is treated as rigid.
Status checkSkinBindings(const Ctx& c, Character& ch) {
  std::vector<int> skinOfMesh(ch.meshes.size(), -2);  // -2 unused, -1 no skin
  for (size_t i = 0; i < ch.nodes.size(); ++i) {
    const Node& n = ch.nodes[i];
    if (n.mesh < 0) continue;
    Mesh& mesh = ch.meshes[n.mesh];
    if (n.skin < 0) continue;
    const size_t jointCount = ch.skins[n.skin].joints.size();
    uint32_t maxJoint = 0;
    for (size_t v = 0; v < mesh.joints0.size(); ++v)
      for (int k = 0; k < 4; ++k) {
        if (mesh.weights0[v][k] > 0.0f) maxJoint = std::max(maxJoint, mesh.joints0[v][k]);
        if (!mesh.weights1.empty() && mesh.weights1[v][k] > 0.0f) maxJoint = std::max(maxJoint, mesh.joints1[v][k]);
      }
    if (maxJoint >= jointCount)
      return err(c, meshLabel(c.m, n.mesh), "joint index " + std::to_string(maxJoint) + " out of range (skin " +
                                                std::to_string(n.skin) + " has " + std::to_string(jointCount) +
                                                " joints)");
    skinOfMesh[n.mesh] = n.skin;
  }
  for (size_t i = 0; i < ch.nodes.size(); ++i) {
    const Node& n = ch.nodes[i];
    if (n.mesh < 0 || n.skin >= 0 || skinOfMesh[n.mesh] >= 0) continue;
    Mesh& mesh = ch.meshes[n.mesh];
    const bool skinned = std::any_of(mesh.joints0.begin(), mesh.joints0.end(), [](const glm::uvec4& j) { return j != glm::uvec4(0); });
    if (skinned) {
      c.report.warnings.push_back(meshLabel(c.m, n.mesh) + ": has skin weights but " + nodeLabel(c.m, static_cast<int>(i)) +
                                  " has no skin; drawn rigidly");
      std::fill(mesh.joints0.begin(), mesh.joints0.end(), glm::uvec4(0));
      std::fill(mesh.weights0.begin(), mesh.weights0.end(), glm::vec4(1, 0, 0, 0));
      mesh.joints1.clear();
      mesh.weights1.clear();
    }
  }
  return {};
}

TextureWrap wrapMode(int gl) {
  if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::ClampToEdge;
  if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::MirroredRepeat;
  return TextureWrap::Repeat;
}

// NEAREST and the NEAREST_MIPMAP_* minification filters sample the nearest texel (no mipmaps here).
TextureFilter filterMode(int gl) {
  return gl == TINYGLTF_TEXTURE_FILTER_NEAREST || gl == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                 gl == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR
             ? TextureFilter::Nearest
             : TextureFilter::Linear;
}

// Decodes glTF texture `tex` (its image, file or bufferView, and its sampler) into
// ch.textures; returns its index, or -1 with a warning naming the image and the reason.
int readTexture(const Ctx& c, int tex, const std::string& materialLabel, Character& ch) {
  const auto& m = c.m;
  const int src = m.textures[tex].source;
  if (src < 0 || src >= int(m.images.size())) {
    c.report.warnings.push_back(materialLabel + ": base colour texture " + std::to_string(tex) +
                                " has no image; drawn in its factor colour");
    return -1;
  }
  const auto& img = m.images[src];
  const bool embedded = img.uri.empty() || img.uri.rfind("data:", 0) == 0;
  const std::string name = embedded ? "image " + std::to_string(src) + " (embedded)" : img.uri;
  Result<TextureImage> t = img.image.empty()
                               ? Result<TextureImage>(Error{name + ": not loaded (missing file or bufferView)"})
                               : decodeTextureImage(img.image.data(), img.image.size(), name);
  if (!t) {
    c.report.warnings.push_back(c.file + ": " + materialLabel + ": texture " + t.error() + "; drawn in its factor colour");
    return -1;
  }
  const int smp = m.textures[tex].sampler;
  if (smp >= 0 && smp < int(m.samplers.size())) {
    const auto& sm = m.samplers[smp];
    t->wrapS = wrapMode(sm.wrapS);
    t->wrapT = wrapMode(sm.wrapT);
    t->magFilter = filterMode(sm.magFilter);
    t->minFilter = filterMode(sm.minFilter);
  }
  ch.textures.push_back(std::move(*t));
  return int(ch.textures.size()) - 1;
}

// Base colour factor and texture of every material (Character::materials, by glTF index);
// each glTF texture a material uses is decoded once.
void readMaterials(const Ctx& c, Character& ch) {
  const auto& m = c.m;
  std::map<int, int> decoded;  // glTF texture -> ch.textures index (or -1)
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const auto& gm = m.materials[i];
    Material mat;
    mat.name = gm.name.empty() ? "material " + std::to_string(i) : gm.name;
    const auto& f = gm.pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4 && std::all_of(f.begin(), f.end(), [](double v) { return std::isfinite(v); }))
      mat.baseColorFactor = glm::clamp(glm::vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3])), 0.0f, 1.0f);
    const int tex = gm.pbrMetallicRoughness.baseColorTexture.index;
    if (tex >= 0 && tex < int(m.textures.size())) {
      const int src = m.textures[tex].source;
      if (src >= 0 && src < int(m.images.size())) {
        const std::string& uri = m.images[src].uri;
        if (uri.empty() || uri.rfind("data:", 0) == 0) mat.baseColorTextureEmbedded = true;
        else mat.baseColorTextureUri = uri;  // inside the file's folder: the file-system guard read it
      }
      auto it = decoded.find(tex);
      if (it == decoded.end()) it = decoded.emplace(tex, readTexture(c, tex, "material '" + mat.name + "'", ch)).first;
      mat.baseColorTexture = it->second;
    }
    ch.materials.push_back(std::move(mat));
  }
}

void listUnsupportedFeatures(const Ctx& c) {
  const auto& m = c.m;
  for (const auto& e : m.extensionsUsed)
    if (e != "KHR_texture_transform") c.report.unsupported.push_back("extension " + e);  // read by readMaterials
  if (!m.lights.empty()) c.report.unsupported.push_back("lights (" + std::to_string(m.lights.size()) + ")");
  if (!m.cameras.empty()) c.report.unsupported.push_back("cameras (" + std::to_string(m.cameras.size()) + ")");
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const auto& mat = m.materials[i];
    const std::string label = "material '" + (mat.name.empty() ? std::to_string(i) : mat.name) + "'";
    if (mat.normalTexture.index >= 0) c.report.unsupported.push_back("normal texture (" + label + ")");
    if (mat.occlusionTexture.index >= 0) c.report.unsupported.push_back("occlusion texture (" + label + ")");
    if (mat.emissiveTexture.index >= 0) c.report.unsupported.push_back("emissive texture (" + label + ")");
    if (mat.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
      c.report.unsupported.push_back("metallic-roughness texture (" + label + ")");
  }
}

// References to each accessor (from primitives, skins and animation
// channels); an accessor referenced more than once is decoded once.
std::vector<int> countAccessorUses(const tinygltf::Model& m) {
  std::vector<int> uses(m.accessors.size(), 0);
  auto use = [&](int i) {
    if (i >= 0 && i < static_cast<int>(uses.size())) ++uses[i];
  };
  for (const auto& mesh : m.meshes)
    for (const auto& prim : mesh.primitives) {
      use(prim.indices);
      for (const auto& [name, acc] : prim.attributes) use(acc);
      for (const auto& target : prim.targets)
        for (const auto& [name, acc] : target) use(acc);
    }
  for (const auto& skin : m.skins) use(skin.inverseBindMatrices);
  for (const auto& anim : m.animations)
    for (const auto& ch : anim.channels)
      if (ch.sampler >= 0 && ch.sampler < static_cast<int>(anim.samplers.size())) {
        use(anim.samplers[ch.sampler].input);
        use(anim.samplers[ch.sampler].output);
      }
  return uses;
}

void dedupe(std::vector<std::string>& v) {
  std::set<std::string> seen;
  std::vector<std::string> out;
  for (auto& s : v)
    if (seen.insert(s).second) out.push_back(std::move(s));
  v.swap(out);
}

std::vector<std::string> splitLines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) out.push_back(line);
  return out;
}

std::string lowerExtension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return e;
}

// The first bytes of a file, quoted when printable, else in hex: "'PK\\x03\\x04'".
std::string describeMagic(const std::string& data) {
  if (data.empty()) return "nothing (the file is empty)";
  std::string out = "'";
  for (size_t i = 0; i < std::min<size_t>(4, data.size()); ++i) {
    const unsigned char ch = static_cast<unsigned char>(data[i]);
    if (ch >= 0x20 && ch < 0x7f && ch != '\\' && ch != '\'') {
      out += char(ch);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", ch);
      out += hex;
    }
  }
  return out + "'";
}

Result<Character> importImpl(const std::string& path) {
  const std::string& file = path;  // messages name the path as given
  auto bytes = readFile(path);
  if (!bytes) return Error{bytes.error()};
  const std::string& data = *bytes;
  const bool binary = data.size() >= 4 && data.compare(0, 4, "glTF") == 0;
  std::error_code ec;
  fs::path dir = fs::weakly_canonical(fs::absolute(fs::path(path), ec).parent_path(), ec);
  if (ec) return Error{file + ": cannot resolve its directory: " + ec.message()};

  if (!binary && lowerExtension(path) == ".glb")
    return Error{file + ": not a glTF binary: it starts with " + describeMagic(data) +
                 " where a .glb file starts with the magic 'glTF'"};

  std::vector<std::string> schemaWarnings;
  std::string withoutPointerChannels;  // the file less the channels tinygltf cannot read, when it has any
  if (auto s = checkGltfSchema(*bytes, file, schemaWarnings, &withoutPointerChannels); !s) return Error{s.error()};
  const std::string& loaded = withoutPointerChannels.empty() ? data : withoutPointerChannels;

  FsGuard guard;
  guard.baseDir = dir.string();
  while (guard.baseDir.size() > 1 && guard.baseDir.back() == '/') guard.baseDir.pop_back();
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({guardedFileExists, identityExpand, guardedReadWholeFile, refuseWrite, &guard});
  loader.SetImageLoader(keepEncodedImage, nullptr);
  tinygltf::Model model;
  std::string terr, twarn;
  bool ok;
  if (binary)
    ok = loader.LoadBinaryFromMemory(&model, &terr, &twarn, reinterpret_cast<const unsigned char*>(loaded.data()),
                                     static_cast<unsigned int>(loaded.size()), guard.baseDir);
  else
    ok = loader.LoadASCIIFromString(&model, &terr, &twarn, loaded.data(), static_cast<unsigned int>(loaded.size()),
                                    guard.baseDir);
  if (!guard.rejectedUri.empty())
    return Error{file + ": uri '" + guard.rejectedUri + "': " + guard.rejectReason};
  if (!ok) {
    if (!guard.missingUri.empty()) return Error{file + ": uri '" + guard.missingUri + "': file not found"};
    if (!guard.unreadable.empty()) return Error{file + ": " + guard.unreadable};
    auto lines = splitLines(terr);
    std::string reason = lines.empty() ? "not a valid glTF file" : lines.front();
    for (size_t i = 1; i < lines.size() && i < 3; ++i) reason += "; " + lines[i];
    return Error{file + ": " + reason};
  }

  Character ch;
  ch.sourcePath = path;
  ch.format = "glTF";
  size_t inputBytes = data.size();
  for (const auto& b : model.buffers) inputBytes += b.data.size();
  Ctx c{file, model, ch.report};
  c.budget = kGltfDecodeFactor * inputBytes + kGltfDecodeAllowance;
  c.uses = countAccessorUses(model);
  ch.report.warnings = std::move(schemaWarnings);
  for (auto& w : splitLines(twarn)) ch.report.warnings.push_back(w);
  if (!guard.missingUri.empty()) ch.report.warnings.push_back("uri '" + guard.missingUri + "': file not found");
  for (const auto& e : model.extensionsRequired)
    if (e != "KHR_materials_unlit" && e != "KHR_texture_transform")
      return err(c, "extensionsRequired", "requires " + e + ", which is not supported");
  listUnsupportedFeatures(c);
  readMaterials(c, ch);
  if (auto s = readHierarchy(c, ch); !s) return Error{s.error()};
  for (int i = 0; i < static_cast<int>(model.meshes.size()); ++i) {
    auto mesh = readMesh(c, i);
    if (!mesh) return Error{mesh.error()};
    ch.meshes.push_back(std::move(*mesh));
  }
  if (auto s = applyNodeMorphWeights(c, ch); !s) return Error{s.error()};
  if (auto s = readSkins(c, ch); !s) return Error{s.error()};
  if (auto s = checkSkinBindings(c, ch); !s) return Error{s.error()};
  if (auto s = readAnimations(c, ch); !s) return Error{s.error()};
  if (ch.meshes.empty()) ch.report.warnings.push_back("no meshes");
  dedupe(ch.report.warnings);
  dedupe(ch.report.unsupported);
  return ch;
}

}  // namespace

Result<Character> importGltf(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  try {
    auto r = importImpl(path);
    if (r) r->report.importMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return r;
  } catch (const std::exception& e) {
    return Error{path + ": cannot be read: " + e.what()};
  } catch (...) {
    return Error{path + ": cannot be read: unknown failure"};
  }
}

bool isGltfPath(const std::string& path) {
  const std::string e = lowerExtension(path);
  if (e == ".gltf" || e == ".glb") return true;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  char magic[4] = {};
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  const size_t n = std::fread(magic, 1, sizeof magic, f);
  std::fclose(f);
  return n == 4 && std::memcmp(magic, "glTF", 4) == 0;
}

}  // namespace animorph
