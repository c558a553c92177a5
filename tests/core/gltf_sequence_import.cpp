#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include <glm/geometric.hpp>

#include "core/io/gltf_sequence_export.h"
#include "core/io/gltf_sequence_import.h"
#include "util/temp_dir.h"

using namespace animorph;
using animorph::test::TempDir;

namespace {

// An octahedron of radius r around (cx, 0, 0) with its vertex normals (unit, along the axes), and
// one tilted normal when asked (not a power-of-two direction: re-normalising may move its last bit).
TriangleMesh octahedron(float cx, float r, bool tilted = false, bool colors = false) {
  TriangleMesh m;
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& a : axes) {
    m.positions.push_back(glm::vec3(cx, 0, 0) + r * a);
    m.normals.push_back(a);
  }
  if (tilted) m.normals[0] = glm::normalize(glm::vec3(1.0f, 0.3f, 0.1f));
  m.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  if (colors)
    for (int i = 0; i < 6; ++i) m.colors.push_back({i / 5.0f, 0.25f, 1.0f - i / 5.0f, 1.0f});
  return m;
}

Status writeSequence(const std::vector<TriangleMesh>& frames, const std::string& name, int first,
                     const std::string& path) {
  GltfSequenceOptions o;
  o.name = name;
  o.firstFrame = first;
  GltfSequenceWriter w(o);
  for (const TriangleMesh& m : frames)
    if (Status st = w.addFrame(m); !st) return st;
  return writeGltfSequence(w, path);
}

}  // namespace

TEST_CASE("glTF sequence read back: every frame's mesh as written, empty and repeated frames too",
          "[io][gltf_sequence]") {
  TempDir dir;
  const std::vector<TriangleMesh> frames = {octahedron(0, 1), octahedron(0, 1), octahedron(2, 0.5f, true),
                                            TriangleMesh{}, octahedron(4, 2, false, true)};
  REQUIRE(writeSequence(frames, "morph", 20, dir.file("a.glb")).ok());
  auto back = readGltfSequence(dir.file("a.glb"), "morph");
  REQUIRE(back.ok());
  REQUIRE(back->size() == frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    const SequenceFrame& f = (*back)[i];
    CHECK(f.frame == 20 + int(i));
    CHECK(f.mesh.positions == frames[i].positions);
    CHECK(f.mesh.indices == frames[i].indices);
    CHECK(f.mesh.colors == frames[i].colors);
    REQUIRE(f.mesh.normals.size() == frames[i].normals.size());
    for (size_t v = 0; v < f.mesh.normals.size(); ++v)
      CHECK(glm::length(f.mesh.normals[v] - frames[i].normals[v]) < 1e-6f);
  }
  // Written again (the assembly of a farm's chunks), the frames give the same file: the axis
  // normals come back exactly, and so does the tilted one here.
  std::vector<TriangleMesh> again;
  for (const SequenceFrame& f : *back) again.push_back(f.mesh);
  REQUIRE(writeSequence(again, "morph", 20, dir.file("b.glb")).ok());
  auto bytes = [](const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  CHECK(bytes(dir.file("a.glb")).size() > 100);
  CHECK(bytes(dir.file("a.glb")) == bytes(dir.file("b.glb")));
}

TEST_CASE("glTF sequence read back: another name, or a file that is not glTF, is an error naming the file",
          "[io][gltf_sequence]") {
  TempDir dir;
  REQUIRE(writeSequence({octahedron(0, 1)}, "morph", 0, dir.file("a.glb")).ok());
  auto other = readGltfSequence(dir.file("a.glb"), "other");
  REQUIRE_FALSE(other.ok());
  CHECK(other.error().find(dir.file("a.glb")) != std::string::npos);
  CHECK(other.error().find("other_####") != std::string::npos);
  auto missing = readGltfSequence(dir.file("none.glb"), "morph");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().find(dir.file("none.glb")) != std::string::npos);
}
