#pragma once
// The binary side of a glTF 2.0 .glb file, shared by the exporters: one
// buffer that bufferViews and accessors are appended to, then the container
// (12-byte header, JSON chunk, BIN chunk) around a caller's JSON document.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace animorph {

namespace gltf {
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
}  // namespace gltf

class GlbWriter {
 public:
  // Appends raw bytes as a new bufferView (4-byte aligned); target 0 leaves it unset. Returns its index.
  int view(const void* data, size_t bytes, int target);
  // Accessor of count elements of componentType and type ("SCALAR", "VEC3", ...) over bufferView v.
  int accessor(int v, int componentType, size_t count, const char* type);
  // Float accessor of count elements with comps components (type "VEC3", ...); minMax adds min/max.
  int floats(const float* data, size_t count, int comps, const char* type, int target, bool minMax);
  // Unit-length NORMAL accessor of unitNormals(n).
  int normals(const std::vector<glm::vec3>& n);
  // Triangle indices encoded by indexBytes.
  int indices(const std::vector<uint32_t>& idx, size_t vertexCount);
  // JOINTS_n accessor (unsigned short VEC4).
  int joints(const std::vector<glm::uvec4>& j);

  // The bytes an accessor's bufferView holds (valid until the next append).
  std::string_view accessorBytes(int accessor) const;

  // n scaled to unit length (zero vectors become +Y: glTF requires unit normals).
  static std::vector<glm::vec3> unitNormals(const std::vector<glm::vec3>& n);
  // Triangle indices as unsigned short when vertexCount fits, else unsigned int
  // (componentType is set to the glTF type used).
  static std::string indexBytes(const std::vector<uint32_t>& idx, size_t vertexCount, int& componentType);

  // The .glb bytes of root with buffers/bufferViews/accessors filled in from what was appended.
  std::string finish(nlohmann::json root);

 private:
  std::vector<unsigned char> bin_;
  nlohmann::json views_ = nlohmann::json::array();
  nlohmann::json accessors_ = nlohmann::json::array();
};

}  // namespace animorph
