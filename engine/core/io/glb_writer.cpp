#include "core/io/glb_writer.h"

#include <algorithm>
#include <limits>

namespace animorph {

using json = nlohmann::json;

int GlbWriter::view(const void* data, size_t bytes, int target) {
  while (bin_.size() % 4) bin_.push_back(0);
  json v = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
  if (target) v["target"] = target;
  const auto* p = static_cast<const unsigned char*>(data);
  bin_.insert(bin_.end(), p, p + bytes);
  views_.push_back(v);
  return static_cast<int>(views_.size()) - 1;
}

int GlbWriter::accessor(int v, int componentType, size_t count, const char* type) {
  accessors_.push_back({{"bufferView", v}, {"componentType", componentType}, {"count", count}, {"type", type}});
  return static_cast<int>(accessors_.size()) - 1;
}

int GlbWriter::floats(const float* data, size_t count, int comps, const char* type, int target, bool minMax) {
  const int a = accessor(view(data, count * comps * sizeof(float), target), gltf::kFloat, count, type);
  if (minMax && count > 0) {
    json mn = json::array(), mx = json::array();
    for (int k = 0; k < comps; ++k) {
      float lo = std::numeric_limits<float>::max(), hi = -lo;
      for (size_t i = 0; i < count; ++i) {
        lo = std::min(lo, data[i * comps + k]);
        hi = std::max(hi, data[i * comps + k]);
      }
      mn.push_back(lo);
      mx.push_back(hi);
    }
    accessors_[a]["min"] = mn;
    accessors_[a]["max"] = mx;
  }
  return a;
}

std::vector<glm::vec3> GlbWriter::unitNormals(const std::vector<glm::vec3>& n) {
  std::vector<glm::vec3> unit(n);
  for (auto& v : unit) {
    const float len = glm::length(v);
    v = len > 1e-20f ? v / len : glm::vec3(0, 1, 0);
  }
  return unit;
}

int GlbWriter::normals(const std::vector<glm::vec3>& n) {
  const std::vector<glm::vec3> unit = unitNormals(n);
  return floats(&unit.data()->x, unit.size(), 3, "VEC3", gltf::kArrayBuffer, false);
}

std::string GlbWriter::indexBytes(const std::vector<uint32_t>& idx, size_t vertexCount, int& componentType) {
  if (vertexCount <= 65535) {
    std::vector<uint16_t> small(idx.begin(), idx.end());
    componentType = gltf::kUnsignedShort;
    return std::string(reinterpret_cast<const char*>(small.data()), small.size() * 2);
  }
  componentType = gltf::kUnsignedInt;
  return std::string(reinterpret_cast<const char*>(idx.data()), idx.size() * 4);
}

int GlbWriter::indices(const std::vector<uint32_t>& idx, size_t vertexCount) {
  int componentType = 0;
  const std::string bytes = indexBytes(idx, vertexCount, componentType);
  return accessor(view(bytes.data(), bytes.size(), gltf::kElementArrayBuffer), componentType, idx.size(), "SCALAR");
}

std::string_view GlbWriter::accessorBytes(int a) const {
  const json& v = views_[accessors_[a]["bufferView"].get<size_t>()];
  return {reinterpret_cast<const char*>(bin_.data()) + v["byteOffset"].get<size_t>(), v["byteLength"].get<size_t>()};
}

int GlbWriter::joints(const std::vector<glm::uvec4>& j) {
  std::vector<uint16_t> data(j.size() * 4);
  for (size_t i = 0; i < j.size(); ++i)
    for (int k = 0; k < 4; ++k) data[i * 4 + k] = static_cast<uint16_t>(j[i][k]);
  return accessor(view(data.data(), data.size() * 2, gltf::kArrayBuffer), gltf::kUnsignedShort, j.size(), "VEC4");
}

std::string GlbWriter::finish(json root) {
  if (!bin_.empty()) {
    root["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    root["bufferViews"] = views_;
    root["accessors"] = accessors_;
  }
  std::string text = root.dump();
  while (text.size() % 4) text.push_back(' ');
  while (bin_.size() % 4) bin_.push_back(0);
  const uint32_t total = static_cast<uint32_t>(12 + 8 + text.size() + (bin_.empty() ? 0 : 8 + bin_.size()));
  std::string out;
  out.reserve(total);
  auto u32 = [&](uint32_t x) { out.append(reinterpret_cast<const char*>(&x), 4); };
  out.append("glTF", 4);
  u32(2);
  u32(total);
  u32(static_cast<uint32_t>(text.size()));
  out.append("JSON", 4);
  out += text;
  if (!bin_.empty()) {
    u32(static_cast<uint32_t>(bin_.size()));
    out.append("BIN\0", 4);
    out.append(reinterpret_cast<const char*>(bin_.data()), bin_.size());
  }
  return out;
}

}  // namespace animorph
