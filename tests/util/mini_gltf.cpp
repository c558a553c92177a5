#include "util/mini_gltf.h"

#include <fstream>

namespace animorph::test {
namespace {

std::string base64(const std::vector<uint8_t>& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    uint32_t v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == in.size()) {
    uint32_t v = in[i] << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    uint32_t v = (in[i] << 16) | (in[i + 1] << 8);
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

}  // namespace

MiniGltf::MiniGltf() {
  root_["asset"] = {{"version", "2.0"}};
  root_["accessors"] = nlohmann::json::array();
  root_["bufferViews"] = nlohmann::json::array();
  root_["meshes"] = nlohmann::json::array();
  root_["nodes"] = nlohmann::json::array();
}

int MiniGltf::addView(const void* data, size_t bytes, int componentType, size_t count, const char* type) {
  while (bin_.size() % 4) bin_.push_back(0);
  root_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}});
  const auto* p = static_cast<const uint8_t*>(data);
  bin_.insert(bin_.end(), p, p + bytes);
  root_["accessors"].push_back({{"bufferView", root_["bufferViews"].size() - 1},
                                {"componentType", componentType},
                                {"count", count},
                                {"type", type}});
  return static_cast<int>(root_["accessors"].size()) - 1;
}

int MiniGltf::addBytes(const std::vector<uint8_t>& bytes) {
  while (bin_.size() % 4) bin_.push_back(0);
  root_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes.size()}});
  bin_.insert(bin_.end(), bytes.begin(), bytes.end());
  return static_cast<int>(root_["bufferViews"].size()) - 1;
}

static size_t componentsOf(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  return 16;
}

int MiniGltf::addFloats(const std::vector<float>& v, const char* type) {
  return addView(v.data(), v.size() * 4, 5126, v.size() / componentsOf(type), type);
}
int MiniGltf::addU16(const std::vector<uint16_t>& v, const char* type) {
  return addView(v.data(), v.size() * 2, 5123, v.size() / componentsOf(type), type);
}
int MiniGltf::addU8(const std::vector<uint8_t>& v, const char* type) {
  return addView(v.data(), v.size(), 5121, v.size() / componentsOf(type), type);
}

int MiniGltf::addMesh(int positionAccessor, int indexAccessor, const nlohmann::json& extra) {
  nlohmann::json attrs = extra;
  attrs["POSITION"] = positionAccessor;
  nlohmann::json prim = {{"attributes", attrs}};
  if (indexAccessor >= 0) prim["indices"] = indexAccessor;
  root_["meshes"].push_back({{"primitives", nlohmann::json::array({prim})}});
  return static_cast<int>(root_["meshes"].size()) - 1;
}

std::string MiniGltf::write(const std::string& dir, const std::string& name, const std::string& bufferUri) const {
  nlohmann::json j = root_;
  std::vector<uint8_t> bin = bin_;
  while (bin.size() % 4) bin.push_back(0);
  if (bufferUri.empty()) {
    j["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
  } else {
    j["buffers"] = {{{"byteLength", bin.size()}, {"uri", bufferUri}}};
  }
  const std::string path = dir + "/" + name;
  std::ofstream(path) << j.dump(1);
  return path;
}

}  // namespace animorph::test
