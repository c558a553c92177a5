#include "core/io/gltf_sequence_export.h"

#include <cstdio>
#include <functional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/util/atomic_file.h"
#include "core/io/glb_writer.h"

namespace animorph {

using json = nlohmann::json;

namespace {

template <class T>
std::string_view bytesOf(const std::vector<T>& v) {
  return {reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T)};
}

// A stored mesh: its accessors (-1 when the attribute is absent).
struct StoredMesh {
  int position = -1, normal = -1, color = -1, indices = -1;
};

}  // namespace

struct GltfSequenceWriter::Impl {
  GltfSequenceOptions options;
  GlbWriter glb;
  std::vector<int> frameMesh;        // per frame: glTF mesh index, -1 for an empty frame
  std::vector<StoredMesh> meshes;    // per glTF mesh
  std::vector<std::string> meshNames;
  std::unordered_multimap<size_t, int> byHash;  // content hash -> glTF mesh
  bool finished = false;

  std::string frameName(int i) const {
    char buf[16];
    std::snprintf(buf, sizeof buf, "_%04d", options.firstFrame + i);
    return options.name + buf;
  }
};

GltfSequenceWriter::GltfSequenceWriter(GltfSequenceOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
}

GltfSequenceWriter::~GltfSequenceWriter() = default;

int GltfSequenceWriter::frameCount() const { return static_cast<int>(impl_->frameMesh.size()); }
int GltfSequenceWriter::meshCount() const { return static_cast<int>(impl_->meshes.size()); }

Status GltfSequenceWriter::addFrame(const TriangleMesh& m) {
  Impl& s = *impl_;
  if (s.finished) return Error{"the glTF sequence is already finished"};
  const int frame = frameCount();
  const std::string label = "frame " + std::to_string(s.options.firstFrame + frame);
  const size_t nv = m.positions.size();
  if (m.indices.size() % 3 != 0) return Error{label + ": " + std::to_string(m.indices.size()) + " indices is not a whole number of triangles"};
  if (!m.normals.empty() && m.normals.size() != nv)
    return Error{label + ": " + std::to_string(m.normals.size()) + " normals for " + std::to_string(nv) + " vertices"};
  if (!m.colors.empty() && m.colors.size() != nv)
    return Error{label + ": " + std::to_string(m.colors.size()) + " colours for " + std::to_string(nv) + " vertices"};
  for (uint32_t i : m.indices)
    if (i >= nv) return Error{label + ": index " + std::to_string(i) + " out of range (" + std::to_string(nv) + " vertices)"};
  if (m.indices.empty()) {
    s.frameMesh.push_back(-1);
    return Status::success();
  }

  const std::vector<glm::vec3> unit = m.normals.empty() ? std::vector<glm::vec3>{} : GlbWriter::unitNormals(m.normals);
  int indexType = 0;
  const std::string indexBytes = GlbWriter::indexBytes(m.indices, nv, indexType);
  const std::hash<std::string_view> hasher;
  size_t h = hasher(bytesOf(m.positions));
  h = h * 1000003u ^ hasher(indexBytes);
  h = h * 1000003u ^ hasher(bytesOf(unit));
  h = h * 1000003u ^ hasher(bytesOf(m.colors));

  // A repeat of a stored mesh: the same bytes in every accessor.
  auto same = [&](int accessor, std::string_view bytes) {
    return accessor < 0 ? bytes.empty() : s.glb.accessorBytes(accessor) == bytes;
  };
  auto [lo, hi] = s.byHash.equal_range(h);
  for (auto it = lo; it != hi; ++it) {
    const StoredMesh& sm = s.meshes[size_t(it->second)];
    if (same(sm.position, bytesOf(m.positions)) && same(sm.indices, indexBytes) && same(sm.normal, bytesOf(unit)) &&
        same(sm.color, bytesOf(m.colors))) {
      s.frameMesh.push_back(it->second);
      return Status::success();
    }
  }

  StoredMesh sm;
  sm.position = s.glb.floats(&m.positions.data()->x, nv, 3, "VEC3", gltf::kArrayBuffer, true);
  if (!unit.empty()) sm.normal = s.glb.floats(&unit.data()->x, nv, 3, "VEC3", gltf::kArrayBuffer, false);
  if (!m.colors.empty()) sm.color = s.glb.floats(&m.colors.data()->x, nv, 4, "VEC4", gltf::kArrayBuffer, false);
  sm.indices = s.glb.accessor(s.glb.view(indexBytes.data(), indexBytes.size(), gltf::kElementArrayBuffer), indexType,
                              m.indices.size(), "SCALAR");
  const int index = meshCount();
  s.meshes.push_back(sm);
  s.meshNames.push_back(s.frameName(frame));
  s.byHash.emplace(h, index);
  s.frameMesh.push_back(index);
  return Status::success();
}

Result<std::string> GltfSequenceWriter::finish() {
  Impl& s = *impl_;
  if (s.finished) return Error{"the glTF sequence is already finished"};
  const GltfSequenceOptions& o = s.options;
  if (!(o.fps > 0.0)) return Error{"the glTF sequence needs fps > 0"};
  if (o.firstFrame < 0) return Error{"the glTF sequence needs a first frame >= 0"};
  const int n = frameCount();
  if (n == 0) return Error{"the glTF sequence has no frames"};
  s.finished = true;
  GlbWriter& w = s.glb;

  json root;
  root["asset"] = {{"version", "2.0"}, {"generator", "Animorph"}};
  if (o.nodeVisibility) root["extensionsUsed"] = {"KHR_animation_pointer", "KHR_node_visibility"};

  json meshes = json::array();
  for (size_t i = 0; i < s.meshes.size(); ++i) {
    const StoredMesh& sm = s.meshes[i];
    json attrs = {{"POSITION", sm.position}};
    if (sm.normal >= 0) attrs["NORMAL"] = sm.normal;
    if (sm.color >= 0) attrs["COLOR_0"] = sm.color;
    json prim = {{"attributes", attrs}, {"indices", sm.indices}, {"mode", 4}};
    meshes.push_back({{"name", s.meshNames[i]}, {"primitives", json::array({prim})}});
  }
  if (!meshes.empty()) root["meshes"] = meshes;

  // Node 0 is the root; frame i is node i + 1.
  json nodes = json::array();
  std::vector<int> children(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) children[size_t(i)] = i + 1;
  nodes.push_back({{"name", o.name}, {"children", children}});
  for (int i = 0; i < n; ++i) {
    json node = {{"name", s.frameName(i)}};
    if (s.frameMesh[size_t(i)] >= 0) node["mesh"] = s.frameMesh[size_t(i)];
    if (i > 0) {
      node["scale"] = {0.0, 0.0, 0.0};
      if (o.nodeVisibility) node["extensions"]["KHR_node_visibility"] = {{"visible", false}};
    }
    nodes.push_back(node);
  }
  root["nodes"] = nodes;
  root["scene"] = 0;
  root["scenes"] = json::array({{{"name", o.name},
                                 {"nodes", {0}},
                                 {"extras", {{"fps", o.fps}, {"frameStart", o.firstFrame}, {"frameEnd", o.firstFrame + n - 1}}}}});
  if (n == 1) return w.finish(std::move(root));  // nothing to animate

  // The three key patterns (first frame, middle frames, last frame), as scale
  // values and as booleans; each frame's key times index into them.
  auto scaleKeys = [&](std::vector<float> on) {
    std::vector<float> v;
    for (float x : on) v.insert(v.end(), {x, x, x});
    return w.floats(v.data(), on.size(), 3, "VEC3", 0, false);
  };
  auto flagKeys = [&](std::vector<unsigned char> on) {
    return w.accessor(w.view(on.data(), on.size(), 0), gltf::kUnsignedByte, on.size(), "SCALAR");
  };
  const int scaleFirst = scaleKeys({1, 0}), scaleMiddle = n > 2 ? scaleKeys({0, 1, 0}) : -1, scaleLast = scaleKeys({0, 1});
  int flagFirst = -1, flagMiddle = -1, flagLast = -1;
  if (o.nodeVisibility) {
    flagFirst = flagKeys({1, 0});
    flagMiddle = n > 2 ? flagKeys({0, 1, 0}) : -1;
    flagLast = flagKeys({0, 1});
  }
  auto keyTime = [&](int i) { return static_cast<float>((o.firstFrame + i) / o.fps); };

  json channels = json::array(), samplers = json::array();
  for (int i = 0; i < n; ++i) {
    std::vector<float> times;
    if (i > 0) times.push_back(keyTime(0));
    times.push_back(keyTime(i));
    if (i + 1 < n) times.push_back(keyTime(i + 1));
    const int input = w.floats(times.data(), times.size(), 1, "SCALAR", 0, true);
    const bool first = i == 0, last = i + 1 == n;
    samplers.push_back({{"input", input}, {"output", first ? scaleFirst : last ? scaleLast : scaleMiddle}, {"interpolation", "STEP"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", i + 1}, {"path", "scale"}}}});
    if (o.nodeVisibility) {
      samplers.push_back({{"input", input}, {"output", first ? flagFirst : last ? flagLast : flagMiddle}, {"interpolation", "STEP"}});
      const std::string pointer = "/nodes/" + std::to_string(i + 1) + "/extensions/KHR_node_visibility/visible";
      channels.push_back({{"sampler", samplers.size() - 1},
                          {"target", {{"path", "pointer"}, {"extensions", {{"KHR_animation_pointer", {{"pointer", pointer}}}}}}}});
    }
  }
  root["animations"] = json::array({{{"name", o.name}, {"channels", channels}, {"samplers", samplers}}});
  return w.finish(std::move(root));
}

Status writeGltfSequence(GltfSequenceWriter& writer, const std::string& path) {
  auto bytes = writer.finish();
  if (!bytes) return Error{path + ": " + bytes.error()};
  return writeFileAtomic(path, *bytes);
}

}  // namespace animorph
