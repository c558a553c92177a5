#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/io/gltf_import.h"
#include "core/io/gltf_sequence_export.h"
#include "core/rig/pose.h"
#include "util/temp_dir.h"

using namespace animorph;
using animorph::test::TempDir;

namespace {

// A tetrahedron moved by dx (4 vertices, 4 triangles), with colours when asked.
TriangleMesh tetra(float dx, bool colors = false) {
  TriangleMesh m;
  m.positions = {{dx, 0, 0}, {dx + 1, 0, 0}, {dx, 1, 0}, {dx, 0, 1}};
  m.normals = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 2}};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  if (colors) m.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
  return m;
}

nlohmann::json glbJson(const std::string& b) {
  uint32_t len = 0;
  std::memcpy(&len, b.data() + 12, 4);
  return nlohmann::json::parse(b.substr(20, len));
}

}  // namespace

TEST_CASE("glTF sequence: one node per frame, repeats share a mesh, STEP scale keys show one frame at a time",
          "[io][gltf_sequence]") {
  GltfSequenceOptions o;
  o.name = "morph";
  o.fps = 25.0;
  o.firstFrame = 10;
  GltfSequenceWriter w(o);
  // Frames 10..15: A, A (repeat), B, empty, A (repeat after others), C with colours.
  for (const TriangleMesh& m : {tetra(0), tetra(0), tetra(2), TriangleMesh{}, tetra(0), tetra(4, true)})
    REQUIRE(w.addFrame(m).ok());
  CHECK(w.frameCount() == 6);
  CHECK(w.meshCount() == 3);
  auto bytes = w.finish();
  REQUIRE(bytes.ok());
  CHECK_FALSE(w.finish().ok());  // once only

  const nlohmann::json j = glbJson(*bytes);
  REQUIRE(j["nodes"].size() == 7);
  CHECK(j["nodes"][0]["name"] == "morph");
  CHECK(j["nodes"][0]["children"] == nlohmann::json({1, 2, 3, 4, 5, 6}));
  CHECK(j["nodes"][1]["name"] == "morph_0010");
  CHECK(j["nodes"][6]["name"] == "morph_0015");
  CHECK(j["nodes"][1]["mesh"] == 0);
  CHECK(j["nodes"][2]["mesh"] == 0);
  CHECK(j["nodes"][3]["mesh"] == 1);
  CHECK_FALSE(j["nodes"][4].contains("mesh"));
  CHECK(j["nodes"][5]["mesh"] == 0);
  CHECK(j["nodes"][6]["mesh"] == 2);
  CHECK_FALSE(j["meshes"][0]["primitives"][0]["attributes"].contains("COLOR_0"));
  CHECK(j["meshes"][2]["primitives"][0]["attributes"].contains("COLOR_0"));
  CHECK(j["scenes"][0]["extras"]["fps"] == 25.0);
  CHECK(j["scenes"][0]["extras"]["frameStart"] == 10);
  CHECK(j["scenes"][0]["extras"]["frameEnd"] == 15);
  // The optional extensions are used, never required.
  CHECK(j["extensionsUsed"] == nlohmann::json({"KHR_animation_pointer", "KHR_node_visibility"}));
  CHECK_FALSE(j.contains("extensionsRequired"));
  CHECK(j["nodes"][2]["extensions"]["KHR_node_visibility"]["visible"] == false);
  CHECK_FALSE(j["nodes"][1].contains("extensions"));
  const auto& channels = j["animations"][0]["channels"];
  REQUIRE(channels.size() == 12);
  CHECK(channels[1]["target"]["path"] == "pointer");
  CHECK_FALSE(channels[1]["target"].contains("node"));
  CHECK(channels[1]["target"]["extensions"]["KHR_animation_pointer"]["pointer"] ==
        "/nodes/1/extensions/KHR_node_visibility/visible");
  for (const auto& s : j["animations"][0]["samplers"]) CHECK(s["interpolation"] == "STEP");

  // Read back by the importer: the meshes, and at each frame's key time
  // exactly that frame's node has scale 1, the others 0.
  TempDir dir;
  REQUIRE(writeFileAtomic(dir.file("seq.glb"), *bytes).ok());
  auto c = importGltf(dir.file("seq.glb"));
  INFO((c.ok() ? std::string() : c.error()));
  REQUIRE(c.ok());
  REQUIRE(c->nodes.size() == 7);
  REQUIRE(c->meshes.size() == 3);
  CHECK(c->meshes[0].vertexCount() == 4);
  CHECK(c->meshes[2].colors.size() == 4);
  REQUIRE(c->clips.size() == 1);
  for (int f = 10; f <= 15; ++f) {
    for (float dt : {0.0f, 0.5f / 25.0f}) {
      auto locals = sampleLocalTransforms(*c, &c->clips[0], float(f / 25.0) + dt);
      for (int i = 1; i <= 6; ++i) CHECK(locals[size_t(i)].scale == glm::vec3(i == f - 9 ? 1.0f : 0.0f));
    }
  }
  // Before the range the first frame shows, after it the last.
  CHECK(sampleLocalTransforms(*c, &c->clips[0], 0.0f)[1].scale == glm::vec3(1.0f));
  CHECK(sampleLocalTransforms(*c, &c->clips[0], 100.0f)[6].scale == glm::vec3(1.0f));
  CHECK(sampleLocalTransforms(*c, &c->clips[0], 100.0f)[5].scale == glm::vec3(0.0f));
}

TEST_CASE("glTF sequence: normals are written unit length, a frame differing only in normals is not a repeat",
          "[io][gltf_sequence]") {
  GltfSequenceWriter w(GltfSequenceOptions{});
  TriangleMesh a = tetra(0), b = tetra(0);
  b.normals[0] = {0, 0, -1};
  REQUIRE(w.addFrame(a).ok());
  REQUIRE(w.addFrame(b).ok());
  TriangleMesh scaled = a;
  for (auto& n : scaled.normals) n *= 2.0f;  // the same unit normals, bit for bit (a power of two)
  REQUIRE(w.addFrame(scaled).ok());
  CHECK(w.meshCount() == 2);
  auto bytes = w.finish();
  REQUIRE(bytes.ok());
  TempDir dir;
  REQUIRE(writeFileAtomic(dir.file("n.glb"), *bytes).ok());
  auto c = importGltf(dir.file("n.glb"));
  REQUIRE(c.ok());
  for (const auto& n : c->meshes[0].normals) CHECK(glm::length(n) == Approx(1.0f));
}

TEST_CASE("glTF sequence: bad frames are refused naming the frame, no file is left on failure", "[io][gltf_sequence]") {
  GltfSequenceOptions o;
  o.firstFrame = 7;
  GltfSequenceWriter w(o);
  TriangleMesh bad = tetra(0);
  bad.indices[4] = 9;
  Status st = w.addFrame(bad);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().find("frame 7") != std::string::npos);
  CHECK(st.error().find("index 9") != std::string::npos);
  CHECK(w.frameCount() == 0);
  TriangleMesh wrongNormals = tetra(0);
  wrongNormals.normals.pop_back();
  CHECK_FALSE(w.addFrame(wrongNormals).ok());

  TempDir dir;
  const std::string path = dir.file("none.glb");
  Status empty = writeGltfSequence(w, path);
  REQUIRE_FALSE(empty.ok());
  CHECK(empty.error().find("none.glb") != std::string::npos);
  CHECK(empty.error().find("no frames") != std::string::npos);
  CHECK(std::filesystem::is_empty(dir.path()));

  GltfSequenceWriter one(GltfSequenceOptions{});
  REQUIRE(one.addFrame(tetra(0)).ok());
  CHECK_FALSE(writeGltfSequence(one, dir.file("missing/dir/x.glb")).ok());
  CHECK(std::filesystem::is_empty(dir.path()));

  GltfSequenceOptions badFps;
  badFps.fps = 0.0;
  GltfSequenceWriter z(badFps);
  REQUIRE(z.addFrame(tetra(0)).ok());
  CHECK_FALSE(z.finish().ok());
}

TEST_CASE("glTF sequence: a single frame has no animation", "[io][gltf_sequence]") {
  GltfSequenceWriter w(GltfSequenceOptions{});
  REQUIRE(w.addFrame(tetra(0)).ok());
  auto bytes = w.finish();
  REQUIRE(bytes.ok());
  const nlohmann::json j = glbJson(*bytes);
  CHECK_FALSE(j.contains("animations"));
  CHECK(j["nodes"].size() == 2);
  CHECK_FALSE(j["nodes"][1].contains("scale"));
}
