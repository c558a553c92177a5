#include "poly/mesh_io.h"

#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "doc/atomic_file.h"

namespace animorph {

namespace {

template <class T>
void append(std::string& s, const T& v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

void appendFloats(std::string& s, const std::vector<glm::vec3>& v) {
  s.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(glm::vec3));
}

}  // namespace

Status writeObj(const TriangleMesh& m, const std::string& path) {
  std::string s;
  s.reserve(m.positions.size() * 64 + m.indices.size() * 12);
  s += "# animorph polygonizer: " + std::to_string(m.positions.size()) + " vertices, " +
       std::to_string(m.triangleCount()) + " triangles\n";
  char buf[128];
  for (const auto& p : m.positions) {
    int n = std::snprintf(buf, sizeof buf, "v %.7g %.7g %.7g\n", p.x, p.y, p.z);
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
  s += "element face " + std::to_string(m.triangleCount()) + "\n";
  s += "property list uchar uint vertex_indices\nend_header\n";
  for (size_t i = 0; i < m.positions.size(); ++i) {
    append(s, m.positions[i]);
    if (normals) append(s, m.normals[i]);
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
  if (m.positions.empty() || m.indices.empty()) {
    // glTF forbids empty buffers and accessors: an empty scene instead.
    std::string js = json{{"asset", {{"version", "2.0"}, {"generator", "animorph polygonizer"}}},
                          {"scene", 0},
                          {"scenes", json::array({json::object()})}}
                         .dump();
    while (js.size() % 4) js.push_back(' ');
    std::string out;
    append(out, uint32_t(0x46546C67));
    append(out, uint32_t(2));
    append(out, uint32_t(12 + 8 + js.size()));
    append(out, uint32_t(js.size()));
    append(out, uint32_t(0x4E4F534A));
    return out + js;
  }
  bool normals = m.normals.size() == m.positions.size() && !m.positions.empty();
  std::string bin;
  appendFloats(bin, m.positions);
  size_t posBytes = bin.size();
  if (normals) appendFloats(bin, m.normals);
  size_t nrmBytes = bin.size() - posBytes;
  size_t idxOffset = bin.size();
  bin.append(reinterpret_cast<const char*>(m.indices.data()), m.indices.size() * sizeof(uint32_t));
  size_t idxBytes = bin.size() - idxOffset;
  while (bin.size() % 4) bin.push_back('\0');

  glm::vec3 lo(0.0f), hi(0.0f);
  if (!m.positions.empty()) {
    lo = hi = m.positions[0];
    for (const auto& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "animorph polygonizer"}};
  j["scene"] = 0;
  j["scenes"] = json::array({{{"nodes", {0}}}});
  j["nodes"] = json::array({{{"mesh", 0}, {"name", "isosurface"}}});
  json attributes = {{"POSITION", 0}};
  json views = json::array();
  json accessors = json::array();
  views.push_back({{"buffer", 0}, {"byteOffset", 0}, {"byteLength", posBytes}, {"target", 34962}});
  accessors.push_back({{"bufferView", 0},
                       {"componentType", 5126},
                       {"count", m.positions.size()},
                       {"type", "VEC3"},
                       {"min", {lo.x, lo.y, lo.z}},
                       {"max", {hi.x, hi.y, hi.z}}});
  if (normals) {
    views.push_back({{"buffer", 0}, {"byteOffset", posBytes}, {"byteLength", nrmBytes}, {"target", 34962}});
    accessors.push_back({{"bufferView", 1}, {"componentType", 5126}, {"count", m.normals.size()}, {"type", "VEC3"}});
    attributes["NORMAL"] = 1;
  }
  views.push_back({{"buffer", 0}, {"byteOffset", idxOffset}, {"byteLength", idxBytes}, {"target", 34963}});
  accessors.push_back({{"bufferView", views.size() - 1},
                       {"componentType", 5125},
                       {"count", m.indices.size()},
                       {"type", "SCALAR"}});
  json prim = {{"attributes", attributes}, {"indices", accessors.size() - 1}, {"mode", 4}};
  j["meshes"] = json::array({{{"primitives", json::array({prim})}, {"name", "isosurface"}}});
  j["bufferViews"] = views;
  j["accessors"] = accessors;
  j["buffers"] = json::array({{{"byteLength", bin.size()}}});
  std::string js = j.dump();
  while (js.size() % 4) js.push_back(' ');

  std::string out;
  uint32_t total = uint32_t(12 + 8 + js.size() + 8 + bin.size());
  append(out, uint32_t(0x46546C67));  // "glTF"
  append(out, uint32_t(2));
  append(out, total);
  append(out, uint32_t(js.size()));
  append(out, uint32_t(0x4E4F534A));  // "JSON"
  out += js;
  append(out, uint32_t(bin.size()));
  append(out, uint32_t(0x004E4942));  // "BIN\0"
  out += bin;
  return out;
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
