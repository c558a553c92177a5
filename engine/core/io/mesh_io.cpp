#include "core/io/mesh_io.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/math/color.h"
#include "core/util/atomic_file.h"
#include "core/io/glb_writer.h"

namespace animorph {

namespace {

template <class T>
void append(std::string& s, const T& v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

}  // namespace

Status writeObj(const TriangleMesh& m, const std::string& path) {
  std::string s;
  s.reserve(m.positions.size() * 64 + m.indices.size() * 12);
  s += "# animorph polygonizer: " + std::to_string(m.positions.size()) + " vertices, " +
       std::to_string(m.triangleCount()) + " triangles\n";
  char buf[128];
  const bool colors = m.colors.size() == m.positions.size();
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec3& p = m.positions[i];
    const glm::vec3 c = colors ? linearToSrgb(glm::vec3(m.colors[i])) : glm::vec3(0.0f);
    int n = colors ? std::snprintf(buf, sizeof buf, "v %.7g %.7g %.7g %.4f %.4f %.4f\n", p.x, p.y, p.z, c.r, c.g, c.b)
                   : std::snprintf(buf, sizeof buf, "v %.7g %.7g %.7g\n", p.x, p.y, p.z);
    s.append(buf, size_t(n));
  }
  bool normals = m.normals.size() == m.positions.size();
  if (normals)
    for (const auto& p : m.normals) {
      int n = std::snprintf(buf, sizeof buf, "vn %.5f %.5f %.5f\n", p.x, p.y, p.z);
      s.append(buf, size_t(n));
    }
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    uint32_t a = m.indices[i] + 1, b = m.indices[i + 1] + 1, c = m.indices[i + 2] + 1;
    int n = normals ? std::snprintf(buf, sizeof buf, "f %u//%u %u//%u %u//%u\n", a, a, b, b, c, c)
                    : std::snprintf(buf, sizeof buf, "f %u %u %u\n", a, b, c);
    s.append(buf, size_t(n));
  }
  return writeFileAtomic(path, s);
}

Status writePly(const TriangleMesh& m, const std::string& path) {
  bool normals = m.normals.size() == m.positions.size();
  std::string s = "ply\nformat binary_little_endian 1.0\ncomment animorph polygonizer\n";
  s += "element vertex " + std::to_string(m.positions.size()) + "\n";
  s += "property float x\nproperty float y\nproperty float z\n";
  if (normals) s += "property float nx\nproperty float ny\nproperty float nz\n";
  const bool colors = m.colors.size() == m.positions.size();
  if (colors) s += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
  s += "element face " + std::to_string(m.triangleCount()) + "\n";
  s += "property list uchar uint vertex_indices\nend_header\n";
  for (size_t i = 0; i < m.positions.size(); ++i) {
    append(s, m.positions[i]);
    if (normals) append(s, m.normals[i]);
    if (colors) {
      const glm::vec4 c(linearToSrgb(glm::vec3(m.colors[i])), std::clamp(m.colors[i].a, 0.0f, 1.0f));
      for (int k = 0; k < 4; ++k) append(s, uint8_t(std::lround(c[k] * 255.0f)));
    }
  }
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    append(s, uint8_t(3));
    append(s, m.indices[i]);
    append(s, m.indices[i + 1]);
    append(s, m.indices[i + 2]);
  }
  return writeFileAtomic(path, s);
}

std::string glbBytes(const TriangleMesh& m) {
  using nlohmann::json;
  json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "animorph polygonizer"}};
  j["scene"] = 0;
  GlbWriter w;
  if (m.positions.empty() || m.indices.empty()) {
    // glTF forbids empty buffers and accessors: an empty scene instead.
    j["scenes"] = json::array({json::object()});
    return w.finish(std::move(j));
  }
  j["scenes"] = json::array({{{"nodes", {0}}}});
  j["nodes"] = json::array({{{"mesh", 0}, {"name", "isosurface"}}});
  const size_t nv = m.positions.size();
  json attributes = {{"POSITION", w.floats(&m.positions.data()->x, nv, 3, "VEC3", gltf::kArrayBuffer, true)}};
  if (m.normals.size() == nv) attributes["NORMAL"] = w.normals(m.normals);
  if (m.colors.size() == nv) attributes["COLOR_0"] = w.floats(&m.colors.data()->x, nv, 4, "VEC4", gltf::kArrayBuffer, false);
  const int indices = w.accessor(w.view(m.indices.data(), m.indices.size() * sizeof(uint32_t), gltf::kElementArrayBuffer),
                                 gltf::kUnsignedInt, m.indices.size(), "SCALAR");
  json prim = {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
  j["meshes"] = json::array({{{"primitives", json::array({prim})}, {"name", "isosurface"}}});
  return w.finish(std::move(j));
}

Status writeGlb(const TriangleMesh& m, const std::string& path) { return writeFileAtomic(path, glbBytes(m)); }

Status writeMesh(const TriangleMesh& m, const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".obj") return writeObj(m, path);
  if (ext == ".ply") return writePly(m, path);
  if (ext == ".glb") return writeGlb(m, path);
  return Error{path + ": unknown mesh format '" + ext + "' (use .obj, .ply or .glb)"};
}

}  // namespace animorph
