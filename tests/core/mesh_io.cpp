#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/blobtree/compile.h"
#include "core/util/atomic_file.h"
#include "core/poly/mesh_checks.h"
#include "core/io/mesh_io.h"
#include "core/poly/polygonizer.h"
#include "util/blob_builders.h"
#include "util/temp_dir.h"

using namespace animorph;
using namespace animorph::test;

namespace {

TriangleMesh sphereMesh() {
  FieldProgram p = compileFieldProgram(treeOf(pointNode(1, {0, 0, 0}, 0.5f)), 0.0);
  PolygonizeSettings s;
  s.resolution = 24;
  return polygonize(p, s)->mesh;
}

template <class T>
T readAt(const std::string& s, size_t off) {
  T v;
  std::memcpy(&v, s.data() + off, sizeof(T));
  return v;
}

}  // namespace

TEST_CASE("GLB: header, chunks and accessors describe the mesh", "[mesh_io]") {
  TriangleMesh m = sphereMesh();
  REQUIRE(m.triangleCount() > 100);
  std::string b = glbBytes(m);
  REQUIRE(b.size() % 4 == 0);
  CHECK(readAt<uint32_t>(b, 0) == 0x46546C67u);
  CHECK(readAt<uint32_t>(b, 4) == 2u);
  CHECK(readAt<uint32_t>(b, 8) == b.size());
  uint32_t jsonLen = readAt<uint32_t>(b, 12);
  CHECK(readAt<uint32_t>(b, 16) == 0x4E4F534Au);
  auto j = nlohmann::json::parse(b.substr(20, jsonLen));
  size_t binHeader = 20 + jsonLen;
  uint32_t binLen = readAt<uint32_t>(b, binHeader);
  CHECK(readAt<uint32_t>(b, binHeader + 4) == 0x004E4942u);
  CHECK(binHeader + 8 + binLen == b.size());
  CHECK(j["buffers"][0]["byteLength"] == binLen);
  CHECK(j["asset"]["version"] == "2.0");
  const auto& prim = j["meshes"][0]["primitives"][0];
  const auto& pos = j["accessors"][prim["attributes"]["POSITION"].get<int>()];
  const auto& idx = j["accessors"][prim["indices"].get<int>()];
  CHECK(pos["count"] == m.positions.size());
  CHECK(idx["count"] == m.indices.size());
  CHECK(idx["componentType"] == 5125);
  // The index data round-trips through the binary chunk.
  const auto& view = j["bufferViews"][idx["bufferView"].get<int>()];
  size_t off = binHeader + 8 + view["byteOffset"].get<size_t>();
  for (size_t i = 0; i < m.indices.size(); i += 97) CHECK(readAt<uint32_t>(b, off + 4 * i) == m.indices[i]);
  // Every accessor's view lies inside the buffer, aligned to 4 bytes.
  for (const auto& v : j["bufferViews"]) {
    CHECK(v["byteOffset"].get<size_t>() % 4 == 0);
    CHECK(v["byteOffset"].get<size_t>() + v["byteLength"].get<size_t>() <= binLen);
  }
}

TEST_CASE("OBJ and binary PLY hold the same mesh", "[mesh_io]") {
  TempDir dir;
  TriangleMesh m = sphereMesh();
  REQUIRE(writeMesh(m, dir.file("s.obj")).ok());
  REQUIRE(writeMesh(m, dir.file("s.ply")).ok());
  REQUIRE(writeMesh(m, dir.file("s.glb")).ok());
  CHECK_FALSE(writeMesh(m, dir.file("s.stl")).ok());

  // OBJ: parse back vertices and faces.
  std::ifstream obj(dir.file("s.obj"));
  TriangleMesh back;
  std::string line;
  while (std::getline(obj, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      glm::vec3 p;
      ls >> p.x >> p.y >> p.z;
      back.positions.push_back(p);
    } else if (tag == "f") {
      for (int k = 0; k < 3; ++k) {
        std::string w;
        ls >> w;
        back.indices.push_back(uint32_t(std::stoul(w.substr(0, w.find('/')))) - 1);
      }
    }
  }
  CHECK(back.indices == m.indices);
  REQUIRE(back.positions.size() == m.positions.size());
  CHECK(std::abs(meshVolume(back) - meshVolume(m)) < 1e-5);

  // PLY: header counts and the binary payload size.
  auto ply = readFile(dir.file("s.ply"));
  REQUIRE(ply.ok());
  size_t end = ply->find("end_header\n");
  REQUIRE(end != std::string::npos);
  std::string header = ply->substr(0, end);
  CHECK(header.find("format binary_little_endian 1.0") != std::string::npos);
  CHECK(header.find("element vertex " + std::to_string(m.positions.size())) != std::string::npos);
  CHECK(header.find("element face " + std::to_string(m.triangleCount())) != std::string::npos);
  size_t payload = ply->size() - (end + 11);
  CHECK(payload == m.positions.size() * 24 + m.triangleCount() * 13);
}

TEST_CASE("an empty mesh writes a valid empty GLB scene", "[mesh_io]") {
  std::string b = glbBytes(TriangleMesh{});
  REQUIRE(b.size() % 4 == 0);
  CHECK(readAt<uint32_t>(b, 8) == b.size());
  auto j = nlohmann::json::parse(b.substr(20, readAt<uint32_t>(b, 12)));
  CHECK(j["asset"]["version"] == "2.0");
  CHECK_FALSE(j.contains("buffers"));
}

TEST_CASE("vertex colours: OBJ v x y z r g b and PLY uchar red/green/blue in sRGB, alpha and GLB COLOR_0 as stored",
          "[mesh_io]") {
  TempDir dir;
  TriangleMesh m = sphereMesh();
  m.colors.resize(m.positions.size());
  // Linear 0.5 is sRGB 0.5^(1/2.2) = 0.7297 (186.1 of 255); alpha 0.5 stays 0.5 (128).
  for (size_t i = 0; i < m.colors.size(); ++i) m.colors[i] = {float(i % 2), 0.5f, 1.0f, 0.5f};
  REQUIRE(writeMesh(m, dir.file("c.obj")).ok());
  REQUIRE(writeMesh(m, dir.file("c.ply")).ok());

  std::ifstream obj(dir.file("c.obj"));
  std::string line;
  size_t vertices = 0;
  while (std::getline(obj, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream ls(line.substr(2));
    float x, y, z, r, g, b;
    REQUIRE(bool(ls >> x >> y >> z >> r >> g >> b));
    CHECK(r == float(vertices % 2));
    CHECK(g == Approx(0.7297f).margin(1e-4));
    ++vertices;
  }
  CHECK(vertices == m.positions.size());

  auto ply = readFile(dir.file("c.ply"));
  REQUIRE(ply.ok());
  size_t end = ply->find("end_header\n");
  REQUIRE(end != std::string::npos);
  CHECK(ply->substr(0, end).find("property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n") !=
        std::string::npos);
  CHECK(ply->size() - (end + 11) == m.positions.size() * 28 + m.triangleCount() * 13);
  // The second vertex (odd: red 1) starts after the first's 28 bytes; its colour follows 6 floats.
  CHECK(uint8_t((*ply)[end + 11 + 28 + 24]) == 255);
  CHECK(uint8_t((*ply)[end + 11 + 28 + 25]) == 186);
  CHECK(uint8_t((*ply)[end + 11 + 28 + 27]) == 128);

  auto j = nlohmann::json::parse(glbBytes(m).substr(20, readAt<uint32_t>(glbBytes(m), 12)));
  CHECK(j["meshes"][0]["primitives"][0]["attributes"].contains("COLOR_0"));
  // GLB COLOR_0 keeps linear light: the second vertex's green is 0.5 in the buffer.
  const std::string glb = glbBytes(m);
  const size_t jsonLen = readAt<uint32_t>(glb, 12), bin = 20 + jsonLen + 8;
  const auto& acc = j["accessors"][j["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"].get<int>()];
  const auto& view = j["bufferViews"][acc["bufferView"].get<int>()];
  const size_t at = bin + view.value("byteOffset", size_t(0)) + acc.value("byteOffset", size_t(0)) + 16;
  CHECK(readAt<float>(glb, at + 4) == 0.5f);
}
