#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/io/gltf_import.h"
#include "core/rig/pose.h"
#include "core/rig/skinning.h"
#include "util/mini_gltf.h"
#include "util/temp_dir.h"
#include "util/test_skip.h"

using namespace animorph;
using animorph::test::MiniGltf;
using animorph::test::TempDir;

namespace {

const std::string kShared = ANIMORPH_SHARED_ASSETS;
const std::string kAssimp = "/usr/share/assimp/models/glTF2/";
// Debian's assimp-testmodels (run.sh installs it): a case that reads them skips without them.
#define SKIP_WITHOUT_ASSIMP_MODELS() \
  if (!std::filesystem::exists(kAssimp)) ANIMORPH_SKIP(kAssimp << " not present (Debian package assimp-testmodels)")

bool contains(const std::vector<std::string>& v, const std::string& needle) {
  for (const auto& s : v)
    if (s.find(needle) != std::string::npos) return true;
  return false;
}

// Local matrix built by hand (T * R * S) from a channel key or the rest pose.
glm::mat4 trs(const glm::vec3& t, const glm::quat& r, const glm::vec3& s) {
  return glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
}

// The node's local matrix at key `key` of clip (every channel of these
// Blender files has the same key times), composed without pose.cpp.
glm::mat4 localAtKey(const Character& c, const AnimationClip& clip, int node, size_t key) {
  glm::vec3 t = c.nodes[node].rest.translation, s = c.nodes[node].rest.scale;
  glm::quat r = c.nodes[node].rest.rotation;
  for (const auto& ch : clip.channels) {
    if (ch.node != node) continue;
    const glm::vec4 v = ch.values[key];
    if (ch.path == ChannelPath::Translation) t = glm::vec3(v);
    if (ch.path == ChannelPath::Scale) s = glm::vec3(v);
    if (ch.path == ChannelPath::Rotation) r = glm::normalize(glm::quat(v.w, v.x, v.y, v.z));
  }
  return trs(t, r, s);
}

glm::mat4 globalAtKey(const Character& c, const AnimationClip& clip, int node, size_t key) {
  glm::mat4 m(1.0f);
  for (int n = node; n >= 0; n = c.nodes[n].parent) m = localAtKey(c, clip, n, key) * m;
  return m;
}

// Checks one vertex (the one with the most even two-way split) skinned by hand
// at a key time against skinnedWorldPositions.
void checkHandSkinnedVertex(const Character& c, size_t key) {
  const auto& clip = c.clips[0];
  const int meshNode = c.meshNodes().front();
  const Mesh& mesh = c.meshes[c.nodes[meshNode].mesh];
  const Skin& skin = c.skins[c.nodes[meshNode].skin];
  size_t best = 0;
  for (size_t v = 0; v < mesh.vertexCount(); ++v)
    if (mesh.weights0[v].y > mesh.weights0[best].y) best = v;
  REQUIRE(mesh.weights0[best].y > 0.1f);  // a vertex really shared by two bones
  const float t = clip.channels[0].timesSec[key];
  glm::mat4 blend(0.0f);
  for (int k = 0; k < 4; ++k) {
    const uint32_t j = mesh.joints0[best][k];
    blend += mesh.weights0[best][k] * globalAtKey(c, clip, skin.joints[j], key) * skin.inverseBindMatrices[j];
  }
  const glm::vec3 expected = glm::vec3(globalAtKey(c, clip, meshNode, key) * blend * glm::vec4(mesh.positions[best], 1));
  const auto skinned = skinnedWorldPositions(c, &clip, t);
  CHECK(glm::length(skinned[best] - expected) < 1e-4f);
  // The pose really moves that vertex (the check is not trivially the rest pose).
  CHECK(glm::length(skinned[best] - glm::vec3(globalAtKey(c, clip, meshNode, key) * glm::vec4(mesh.positions[best], 1))) > 1e-3f);
}

void checkBindPoseIsRest(const Character& c) {
  const auto globals = poseGlobals(c, nullptr, 0.0f);
  for (const auto& skin : c.skins)
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const glm::mat4 m = globals[skin.joints[j]] * skin.inverseBindMatrices[j];
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) CHECK(m[a][b] == Approx(a == b ? 1.0f : 0.0f).margin(1e-4));
    }
}

}  // namespace

TEST_CASE("shared asset tentacle.glb imports with its rig and clip", "[io][gltf]") {
  if (!std::filesystem::exists(kShared + "/tentacle.glb")) ANIMORPH_SKIP(kShared << "/tentacle.glb not present");
  auto c = importGltf(kShared + "/tentacle.glb");
  REQUIRE(c.ok());
  CHECK(c->meshes.size() == 1);
  CHECK(c->totalVertices() == 7630);
  CHECK(c->totalTriangles() == 5276);
  CHECK(c->totalJoints() == 6);
  REQUIRE(c->clips.size() == 1);
  CHECK(c->clips[0].name == "ArmatureAction");
  CHECK(c->clips[0].durationSec == Approx(1.875f));
  CHECK(c->clips[0].channels.size() == 18);
  CHECK(c->report.warnings.empty());
  CHECK(c->report.weightsNormalised == 0);
  CHECK(c->report.importMs > 0.0);
  // Weights sum to one everywhere.
  for (const auto& w : c->meshes[0].weights0) CHECK(w.x + w.y + w.z + w.w == Approx(1.0f).margin(1e-5));
  checkBindPoseIsRest(*c);
  checkHandSkinnedVertex(*c, 20);
}

TEST_CASE("shared asset plate.glb imports with its rig and clip", "[io][gltf]") {
  if (!std::filesystem::exists(kShared + "/plate.glb")) ANIMORPH_SKIP(kShared << "/plate.glb not present");
  auto c = importGltf(kShared + "/plate.glb");
  REQUIRE(c.ok());
  CHECK(c->totalVertices() == 4590);
  CHECK(c->totalTriangles() == 2952);
  CHECK(c->totalJoints() == 3);
  REQUIRE(c->clips.size() == 1);
  CHECK(c->clips[0].name == "ArmatureAction");
  CHECK(c->clips[0].durationSec == Approx(1.7916667f));
  CHECK(c->nodes[c->skins[0].joints[0]].name == "root");
  checkBindPoseIsRest(*c);
  checkHandSkinnedVertex(*c, 30);
}

TEST_CASE("malformed files from Debian's assimp test models give named errors", "[io][gltf]") {
  SKIP_WITHOUT_ASSIMP_MODELS();
  auto expectError = [](const std::string& rel, const std::string& message) {
    auto c = importGltf(kAssimp + rel);
    REQUIRE_FALSE(c.ok());
    // Errors name the path as given: here the directory of rel, then message.
    CHECK(c.error() == kAssimp + rel.substr(0, rel.rfind('/') + 1) + message);
  };
  expectError("IndexOutOfRange/IndexOutOfRange.gltf",
              "IndexOutOfRange.gltf: accessor 0: index 255 out of range (24 vertices)");
  expectError("IndexOutOfRange/AllIndicesOutOfRange.gltf",
              "AllIndicesOutOfRange.gltf: accessor 0: index 65535 out of range (24 vertices)");
  expectError("MissingBin/BoxTextured.gltf", "BoxTextured.gltf: uri 'BoxTextured0.bin': file not found");
  expectError("RecursiveNodes/RecursiveNodes.gltf",
              "RecursiveNodes.gltf: node 0: cyclic hierarchy (parent chain 0 -> 1 -> 0)");
  expectError("BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
              "BoxWithInfinites.glb: accessor 2: position 0 is not finite (Inf)");
  expectError("SchemaFailures/sceneWrongType.gltf",
              "sceneWrongType.gltf: scene: expected a non-negative integer index, found string");
  expectError("wrongTypes/badArray.gltf",
              "badArray.gltf: meshes[0].primitives: expected an array of objects, found object");
  expectError("TestNoRootNode/NoScene.gltf", "NoScene.gltf: scene 0: does not exist (0 scenes)");
  // Draco-compressed accessors have no bufferView: tinygltf refuses them.
  auto draco = importGltf(kAssimp + "draco/2CylinderEngine.gltf");
  REQUIRE_FALSE(draco.ok());
  CHECK(draco.error().rfind(kAssimp + "draco/2CylinderEngine.gltf: accessor", 0) == 0);
}

TEST_CASE("wrongly typed material properties are warnings, the geometry still loads", "[io][gltf]") {
  SKIP_WITHOUT_ASSIMP_MODELS();
  const std::pair<const char*, const char*> cases[] = {
      {"badNumber.gltf", "materials[0].normalTexture.scale: expected a number, found string; ignored"},
      {"badObject.gltf", "materials[0].pbrMetallicRoughness: expected an object, found array; ignored"},
      {"badString.gltf", "scenes[0].name: expected a string, found integer; ignored"},
      {"badUint.gltf", "materials[0].pbrMetallicRoughness.baseColorTexture.index: expected a non-negative integer index"},
      {"badExtension.gltf", "extensions.KHR_texture_transform: expected an object, found string; ignored"}};
  for (const auto& [file, warning] : cases) {
    INFO(file);
    auto c = importGltf(kAssimp + "wrongTypes/" + file);
    REQUIRE(c.ok());
    CHECK(c->totalTriangles() == 12);
    CHECK(contains(c->report.warnings, warning));
  }
}

TEST_CASE("IncorrectVertexArrays: truncated triangles warn, lines are listed as unsupported", "[io][gltf]") {
  SKIP_WITHOUT_ASSIMP_MODELS();
  auto c = importGltf(kAssimp + "IncorrectVertexArrays/Cube.gltf");
  REQUIRE(c.ok());
  CHECK(c->meshes[0].triangleCount() == 12);
  CHECK(c->meshes[1].triangleCount() == 11);  // 35 vertices: the last two dropped
  CHECK(c->meshes[2].triangleCount() == 0);
  CHECK(contains(c->report.warnings, "mesh 1 'TruncatedCube' primitive 0: 35 vertices is not a multiple of 3; the last 2 ignored"));
  CHECK(contains(c->report.warnings, "mesh 5 'TruncatedIndexedCube' primitive 0: 35 indices is not a multiple of 3"));
  CHECK(contains(c->report.warnings, "mesh 2 'Lines': no triangles"));
  CHECK(contains(c->report.unsupported, "LINES primitive (mesh 2 'Lines' primitive 0, skipped)"));
  CHECK(c->report.normalsComputed == 4);
}

TEST_CASE("simple_skin imports, and skins a vertex at a hand-computed pose", "[io][gltf]") {
  SKIP_WITHOUT_ASSIMP_MODELS();
  auto c = importGltf(kAssimp + "simple_skin/simple_skin.gltf");
  REQUIRE(c.ok());
  CHECK(c->totalVertices() == 10);
  CHECK(c->totalTriangles() == 8);
  CHECK(c->totalJoints() == 2);
  CHECK(c->report.normalsComputed == 1);
  REQUIRE(c->clips.size() == 1);
  CHECK(c->clips[0].durationSec == Approx(5.5f));
  // Vertex 9 sits at (1, 2, 0) fully on joint 1 (node 2, at (0, 1, 0) under
  // node 1). At t = 1.5 s (key 3) node 2 takes the file's key rotation r, so
  // the vertex goes to T(0, 1, 0) * R * inverseBind * p.
  const auto& ch = c->clips[0].channels[0];
  REQUIRE(ch.timesSec[3] == Approx(1.5f));
  const glm::vec4 q = ch.values[3];
  const glm::quat r = glm::normalize(glm::quat(q.w, q.x, q.y, q.z));
  const Mesh& m = c->meshes[0];
  REQUIRE(m.weights0[9].x == Approx(1.0f));
  REQUIRE(c->skins[0].joints[m.joints0[9].x] == 2);
  const glm::mat4 ibm = c->skins[0].inverseBindMatrices[m.joints0[9].x];
  const glm::vec3 expected =
      glm::vec3(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)) * glm::mat4_cast(r) * ibm * glm::vec4(m.positions[9], 1));
  auto p = skinnedWorldPositions(*c, &c->clips[0], 1.5f);
  CHECK(glm::length(p[9] - expected) < 1e-5f);
  CHECK(glm::length(p[9] - m.positions[9]) > 0.1f);
}

TEST_CASE("triangle strips and fans keep the winding of the triangle list", "[io][gltf]") {
  SKIP_WITHOUT_ASSIMP_MODELS();
  const std::string dir = kAssimp + "glTF-Asset-Generator/Mesh_PrimitiveMode/";
  auto faceNormal = [](const Mesh& m, size_t t) {
    const auto& p = m.positions;
    const auto* i = &m.indices[3 * t];
    return glm::normalize(glm::cross(p[i[1]] - p[i[0]], p[i[2]] - p[i[0]]));
  };
  auto reference = importGltf(dir + "Mesh_PrimitiveMode_13.gltf");
  REQUIRE(reference.ok());
  const glm::vec3 n = faceNormal(reference->meshes[0], 0);
  for (const char* f : {"04", "05", "11", "12"}) {
    INFO(f);
    auto c = importGltf(dir + "Mesh_PrimitiveMode_" + f + ".gltf");
    REQUIRE(c.ok());
    REQUIRE(c->meshes[0].triangleCount() == 2);
    for (size_t t = 0; t < 2; ++t) CHECK(glm::dot(faceNormal(c->meshes[0], t), n) > 0.99f);
  }
  for (const char* f : {"00", "01", "02", "03"}) {
    auto c = importGltf(dir + "Mesh_PrimitiveMode_" + f + ".gltf");
    REQUIRE(c.ok());
    CHECK(c->totalTriangles() == 0);
    CHECK(c->report.unsupported.size() == 1);
  }
}

TEST_CASE("unsupported features are listed by name", "[io][gltf]") {
  SKIP_WITHOUT_ASSIMP_MODELS();
  auto morph = importGltf(kAssimp + "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  REQUIRE(morph.ok());
  // Morph targets and their weight animation are read (core/blend_shapes.cpp); tangent deltas are not.
  CHECK(contains(morph->report.unsupported, "morph target TANGENT deltas (mesh 0 'Cube' primitive 0 morph target 0)"));
  auto cams = importGltf(kAssimp + "cameras/Cameras.gltf");
  REQUIRE(cams.ok());
  CHECK(contains(cams->report.unsupported, "cameras (2)"));
  auto coat = importGltf(kAssimp + "ClearCoat-glTF/ClearCoatTest.gltf");
  REQUIRE(coat.ok());
  CHECK(contains(coat->report.unsupported, "extension KHR_materials_clearcoat"));
  CHECK(contains(coat->report.unsupported, "normal texture (material 'BaseNorm_Base')"));
}

TEST_CASE("external URIs must stay inside the glTF file's directory", "[io][gltf]") {
  TempDir tmp;
  std::filesystem::create_directories(tmp.path() / "sub");
  MiniGltf g;
  int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  g.addMesh(pos, -1);
  g.json()["nodes"].push_back({{"mesh", 0}});
  // The buffer exists, but one level up.
  std::ofstream(tmp.file("secret.bin"), std::ios::binary) << std::string(36, '\0');
  auto escaped = importGltf(g.write((tmp.path() / "sub").string(), "escape.gltf", "../secret.bin"));
  REQUIRE_FALSE(escaped.ok());
  CHECK(escaped.error() == (tmp.path() / "sub" / "escape.gltf").string() + ": uri '../secret.bin': resolves outside the glTF file's directory");
  auto absolute = importGltf(g.write((tmp.path() / "sub").string(), "absolute.gltf", tmp.file("secret.bin")));
  REQUIRE_FALSE(absolute.ok());
  CHECK(absolute.error() == (tmp.path() / "sub" / "absolute.gltf").string() + ": uri '" + tmp.file("secret.bin") + "': absolute paths are not allowed");
  // Beside the file and as a data: URI both load.
  std::filesystem::copy_file(tmp.file("secret.bin"), tmp.path() / "sub" / "ok.bin");
  CHECK(importGltf(g.write((tmp.path() / "sub").string(), "beside.gltf", "ok.bin")).ok());
  auto embedded = importGltf(g.write(tmp.path().string(), "embedded.gltf"));
  REQUIRE(embedded.ok());
  CHECK(embedded->totalTriangles() == 1);
}

TEST_CASE("skin weights: normalised, zero-weight and more than eight influences are counted", "[io][gltf]") {
  TempDir tmp;
  MiniGltf g;
  // Four vertices of two triangles.
  int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3");
  int idx = g.addU16({0, 1, 2, 1, 3, 2}, "SCALAR");
  // Vertex 0 sums to 0.8, vertex 1 to 1.0 (with a repeated joint), vertex 2
  // has no weight, vertex 3 spreads over 9 joints (two sets plus a third).
  int j0 = g.addU8({0, 1, 0, 0, 2, 2, 0, 0, 0, 0, 0, 0, 0, 1, 2, 3}, "VEC4");
  int w0 = g.addFloats({0.5f, 0.3f, 0, 0, 0.5f, 0.5f, 0, 0, 0, 0, 0, 0, 0.2f, 0.15f, 0.15f, 0.1f}, "VEC4");
  int j1 = g.addU16({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 5, 6, 7}, "VEC4");
  int w1 = g.addFloats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.1f, 0.1f, 0.08f, 0.07f}, "VEC4");
  int j2 = g.addU8({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 8, 0, 0, 0}, "VEC4");
  int w2 = g.addFloats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.05f, 0, 0, 0}, "VEC4");
  g.addMesh(pos, idx, {{"JOINTS_0", j0}, {"WEIGHTS_0", w0}, {"JOINTS_1", j1}, {"WEIGHTS_1", w1}, {"JOINTS_2", j2}, {"WEIGHTS_2", w2}});
  auto& nodes = g.json()["nodes"];
  nodes.push_back({{"mesh", 0}, {"skin", 0}});
  std::vector<int> joints;
  for (int j = 0; j < 9; ++j) {
    nodes.push_back({{"name", "j" + std::to_string(j)}, {"translation", {0.1 * j, 0, 0}}});
    joints.push_back(j + 1);
  }
  g.json()["skins"] = {{{"joints", joints}}};
  auto c = importGltf(g.write(tmp.path().string(), "weights.gltf"));
  REQUIRE(c.ok());
  const Mesh& m = c->meshes[0];
  CHECK(c->report.weightsNormalised == 1);  // vertex 0 only
  CHECK(c->report.influencesDropped == 1);  // vertex 3
  CHECK(contains(c->report.warnings, "1 vertices have no skin weight; bound to the skin's first joint"));
  CHECK(m.weights0[0].x == Approx(0.625f));
  CHECK(m.weights0[0].y == Approx(0.375f));
  CHECK(m.joints0[1].x == 2);  // repeated joint 2 merged into one influence of weight 1
  CHECK(m.weights0[1].x == Approx(1.0f));
  CHECK(m.weights0[2] == glm::vec4(1, 0, 0, 0));
  REQUIRE(m.weights1.size() == 4);
  // Vertex 3 keeps the 8 largest (joint 8's 0.05 is dropped), renormalised.
  const float kept = 0.95f;
  CHECK(m.weights0[3].x == Approx(0.2f / kept));
  CHECK(m.joints0[3].x == 0);
  float sum = 0;
  for (int k = 0; k < 4; ++k) sum += m.weights0[3][k] + m.weights1[3][k];
  CHECK(sum == Approx(1.0f));
  for (int k = 0; k < 4; ++k) CHECK(m.joints1[3][k] != 8);
  // Unskinned meshes bind every vertex to joint 0.
  MiniGltf rigid;
  rigid.addMesh(rigid.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3"), -1);
  rigid.json()["nodes"].push_back({{"mesh", 0}});
  auto r = importGltf(rigid.write(tmp.path().string(), "rigid.gltf"));
  REQUIRE(r.ok());
  CHECK(r->meshes[0].joints0 == std::vector<glm::uvec4>(3, glm::uvec4(0)));
  CHECK(r->meshes[0].weights0 == std::vector<glm::vec4>(3, glm::vec4(1, 0, 0, 0)));
  CHECK(r->report.normalsComputed == 1);
  CHECK(glm::length(r->meshes[0].normals[0] - glm::vec3(0, 0, 1)) < 1e-6f);
}

TEST_CASE("structural errors name the element", "[io][gltf]") {
  TempDir tmp;
  auto base = [] {
    MiniGltf g;
    int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    g.addMesh(pos, -1);
    return g;
  };
  {
    MiniGltf g = base();
    g.json()["accessors"][0]["count"] = 4;  // 48 bytes from a 36-byte view
    g.json()["nodes"].push_back({{"mesh", 0}});
    auto c = importGltf(g.write(tmp.path().string(), "bounds.gltf"));
    REQUIRE_FALSE(c.ok());
    CHECK(c.error() == tmp.file("bounds.gltf") + ": accessor 0: 4 elements of 12 bytes at offset 0 exceed bufferView 0 (36 bytes)");
  }
  {
    MiniGltf g = base();
    g.json()["bufferViews"][0]["byteLength"] = 4000;
    g.json()["nodes"].push_back({{"mesh", 0}});
    auto c = importGltf(g.write(tmp.path().string(), "view.gltf"));
    REQUIRE_FALSE(c.ok());
    CHECK(c.error().rfind(tmp.file("view.gltf") + ": bufferView 0: bytes 0..4000 exceed buffer 0", 0) == 0);
  }
  {
    MiniGltf g = base();
    g.json()["accessors"][0]["componentType"] = 5121;  // positions as unsigned bytes
    g.json()["nodes"].push_back({{"mesh", 0}});
    auto c = importGltf(g.write(tmp.path().string(), "types.gltf"));
    REQUIRE_FALSE(c.ok());
    CHECK(c.error() == tmp.file("types.gltf") + ": accessor 0: component type unsigned byte (5121) is wrong for POSITION (expected float)");
  }
  {
    MiniGltf g = base();
    g.json()["nodes"] = {{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}};
    auto c = importGltf(g.write(tmp.path().string(), "parents.gltf"));
    REQUIRE_FALSE(c.ok());
    CHECK(c.error() == tmp.file("parents.gltf") + ": node 2: has two parents (node 0 and node 1)");
  }
  {
    MiniGltf g = base();
    g.json()["nodes"] = {{{"children", {0}}, {"mesh", 0}}};
    auto c = importGltf(g.write(tmp.path().string(), "self.gltf"));
    REQUIRE_FALSE(c.ok());
    CHECK(c.error() == tmp.file("self.gltf") + ": node 0: is its own child (cyclic hierarchy)");
  }
  {
    MiniGltf g = base();
    g.json()["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7;
    g.json()["nodes"].push_back({{"mesh", 0}});
    auto c = importGltf(g.write(tmp.path().string(), "missing.gltf"));
    REQUIRE_FALSE(c.ok());
    CHECK(c.error() == tmp.file("missing.gltf") + ": POSITION refers to accessor 7, which does not exist (1 accessors)");
  }
  {
    MiniGltf g = base();
    g.json()["meshes"].push_back({{"name", "empty"}, {"primitives", nlohmann::json::array()}});
    g.json()["nodes"].push_back({{"mesh", 0}});
    auto c = importGltf(g.write(tmp.path().string(), "empty.gltf"));
    REQUIRE(c.ok());
    CHECK(contains(c->report.warnings, "mesh 1 'empty': no triangles"));
  }
  CHECK_FALSE(importGltf(tmp.file("does-not-exist.glb")).ok());
  std::ofstream(tmp.file("garbage.glb")) << "glTF garbage that is not a GLB";
  auto garbage = importGltf(tmp.file("garbage.glb"));
  REQUIRE_FALSE(garbage.ok());
  CHECK(garbage.error().rfind(tmp.file("garbage.glb") + ": ", 0) == 0);
}

TEST_CASE("animations: all three interpolations, duration is the last key", "[io][gltf]") {
  TempDir tmp;
  MiniGltf g;
  g.addMesh(g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3"), -1);
  g.json()["nodes"].push_back({{"mesh", 0}});
  int t2 = g.addFloats({0.0f, 1.0f}, "SCALAR");
  int t3 = g.addFloats({0.0f, 0.5f, 2.5f}, "SCALAR");
  int trans = g.addFloats({0, 0, 0, 2, 0, 0}, "VEC3");
  int rot = g.addFloats({0, 0, 0, 1, 0, 0, 0.7071068f, 0.7071068f, 0, 0, 1, 0}, "VEC4");
  int cubic = g.addFloats({0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 3, 3, 3, 0, 0, 0}, "VEC3");
  g.json()["animations"] = {{{"name", "mixed"},
                             {"samplers",
                              {{{"input", t2}, {"output", trans}, {"interpolation", "STEP"}},
                               {{"input", t3}, {"output", rot}},
                               {{"input", t2}, {"output", cubic}, {"interpolation", "CUBICSPLINE"}}}},
                             {"channels",
                              {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
                               {{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}},
                               {{"sampler", 2}, {"target", {{"node", 0}, {"path", "scale"}}}}}}}};
  auto c = importGltf(g.write(tmp.path().string(), "anim.gltf"));
  REQUIRE(c.ok());
  REQUIRE(c->clips.size() == 1);
  const auto& clip = c->clips[0];
  CHECK(clip.name == "mixed");
  CHECK(clip.durationSec == Approx(2.5f));
  CHECK(clip.channels[0].interpolation == Interpolation::Step);
  CHECK(clip.channels[1].interpolation == Interpolation::Linear);
  CHECK(clip.channels[2].interpolation == Interpolation::CubicSpline);
  CHECK(clip.channels[2].values.size() == 6);
  auto locals = sampleLocalTransforms(*c, &clip, 0.75f);
  CHECK(locals[0].translation.x == 0.0f);  // STEP holds the first key
  CHECK(locals[0].scale.x == Approx(1.0f + 2.0f * (3 * 0.5625f - 2 * 0.421875f)));
  // A cubic sampler with the wrong value count is refused.
  g.json()["animations"][0]["samplers"][2]["output"] = trans;
  auto bad = importGltf(g.write(tmp.path().string(), "badanim.gltf"));
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error() == tmp.file("badanim.gltf") + ": accessor " + std::to_string(trans) +
                           ": 2 values for 2 keys (CUBICSPLINE needs 6)");
}

TEST_CASE("corrupted files never crash the importer", "[io][gltf]") {
  SKIP_WITHOUT_ASSIMP_MODELS();
  // Deterministic byte mutations of a small skinned GLB (JSON and binary
  // chunks alike): every import either loads or returns a message naming the file.
  TempDir tmp;
  std::ifstream in(kAssimp + "simple_skin/simple_skin.gltf");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto glbSource = importGltf(std::string(ANIMORPH_SOURCE_DIR) + "/resources/demo/gear.glb");
  REQUIRE(glbSource.ok());
  std::ifstream gin(std::string(ANIMORPH_SOURCE_DIR) + "/resources/demo/gear.glb", std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(gin)), std::istreambuf_iterator<char>());
  uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  int loaded = 0, refused = 0;
  for (int round = 0; round < 300; ++round) {
    const bool binary = round % 2 == 0;
    std::string bytes = binary ? glb : text;
    const int flips = 1 + static_cast<int>(next() % 4);
    for (int f = 0; f < flips; ++f) {
      // Binary rounds aim at the JSON chunk half of the time (it holds the offsets and counts).
      const size_t limit = binary && (next() & 1) ? std::min<size_t>(bytes.size(), 2048) : bytes.size();
      const size_t at = next() % limit;
      const char digits[] = "0123456789-9e";
      bytes[at] = binary ? static_cast<char>(next() & 0xff) : digits[next() % 13];
    }
    const std::string path = tmp.file(binary ? "fuzz.glb" : "fuzz.gltf");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    auto c = importGltf(path);
    if (c) ++loaded;
    else {
      ++refused;
      CHECK(c.error().rfind(path + ": ", 0) == 0);
    }
  }
  CHECK(loaded + refused == 300);
  CHECK(refused > 0);
}

TEST_CASE("a .glb that is not a glTF binary is refused naming the file and the magic", "[io][gltf]") {
  TempDir dir;
  const std::string zip = dir.file("Walker.GLB");
  std::ofstream(zip, std::ios::binary) << std::string("PK\x03\x04", 4) << "zip archive, renamed";
  auto r = importGltf(zip);
  REQUIRE_FALSE(r);
  CHECK_THAT(r.error(), Catch::StartsWith(zip + ": not a glTF binary") && Catch::Contains("'PK\\x03\\x04'"));
  CHECK_THAT(r.error(), !Catch::Contains("JSON"));

  const std::string empty = dir.file("empty.glb");
  std::ofstream(empty, std::ios::binary).flush();
  auto e = importGltf(empty);
  REQUIRE_FALSE(e);
  CHECK_THAT(e.error(), Catch::Contains("empty.glb: not a glTF binary") && Catch::Contains("empty"));

  // What the editor's Open takes for a glTF: the extension, or the GLB magic under any name.
  CHECK(isGltfPath(zip));
  CHECK(isGltfPath(dir.file("hero.gltf")));
  const std::string disguised = dir.file("character.bin");
  std::ofstream(disguised, std::ios::binary) << "glTF" << std::string(8, '\0');
  CHECK(isGltfPath(disguised));
  const std::string project = dir.file("scene.animorph");
  std::ofstream(project) << "{}";
  CHECK_FALSE(isGltfPath(project));
  CHECK_FALSE(isGltfPath(dir.file("missing.animorph")));
}
