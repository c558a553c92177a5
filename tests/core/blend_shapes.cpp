// Blend shapes (glTF morph targets): import, weight evaluation, CPU skinning,
// transitions, bakes and export, checked against Blender's own evaluation of a
// character it exported (tests/tools/blender_blend_shape_character.py, made by
// the CTest fixture into ANIMORPH_BLEND_SHAPE_DIR) and a Khronos sample file.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "core/export/project_frames.h"
#include "core/io/gltf_export.h"
#include "core/io/assimp_import.h"
#include "core/io/gltf_import.h"
#include "core/project/new_morph_project.h"
#include "core/standin_morph/transition.h"
#include "core/standin/standin.h"
#include "core/rig/morph_targets.h"
#include "core/rig/pose.h"
#include "core/rig/skinning.h"
#include "util/mini_gltf.h"
#include "util/morph_fixtures.h"
#include "util/temp_dir.h"
#include "util/test_skip.h"

using namespace animorph;
using animorph::test::MiniGltf;
using animorph::test::TempDir;

namespace {

const std::string kMorphCube =
    "/usr/share/assimp/models/glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf";

// Where the fixture wrote Blender's files, or "" (the test then skips).
std::string blenderDir() {
  const char* d = std::getenv("ANIMORPH_BLEND_SHAPE_DIR");
  if (!d || !std::filesystem::exists(std::string(d) + "/blend_shape_reference.json")) return {};
  return d;
}

struct BlenderReference {
  std::vector<glm::vec3> rest, stat;
  std::map<int, std::vector<glm::vec3>> frames;  // frame -> evaluated world positions
  double fps = 24.0;
};

std::vector<glm::vec3> points(const nlohmann::json& j) {
  std::vector<glm::vec3> out;
  for (const auto& p : j) out.push_back({p[0].get<float>(), p[1].get<float>(), p[2].get<float>()});
  return out;
}

BlenderReference readReference(const std::string& dir) {
  std::ifstream in(dir + "/blend_shape_reference.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  BlenderReference r;
  r.rest = points(j["rest"]);
  r.stat = points(j["static"]);
  r.fps = j["fps"].get<double>();
  for (const auto& [f, pts] : j["animated"].items()) r.frames[std::stoi(f)] = points(pts);
  return r;
}

float diagonal(const std::vector<glm::vec3>& pts) {
  Bounds b;
  for (const auto& p : pts) b.add(p);
  return b.diagonal();
}

// For each vertex of ours, the Blender vertex at the same rest position (the
// exporter may reorder vertices); REQUIREs a match within 1e-5 of the diagonal.
std::vector<size_t> matchVertices(const std::vector<glm::vec3>& ours, const std::vector<glm::vec3>& blender) {
  const float tol = 1e-5f * diagonal(blender);
  std::vector<size_t> map(ours.size());
  for (size_t i = 0; i < ours.size(); ++i) {
    size_t best = 0;
    float bestD = 1e30f;
    for (size_t k = 0; k < blender.size(); ++k) {
      const float d = glm::length(ours[i] - blender[k]);
      if (d < bestD) bestD = d, best = k;
    }
    INFO("vertex " << i);
    REQUIRE(bestD <= tol);
    map[i] = best;
  }
  return map;
}

// The largest distance between ours[i] and blender[map[i]].
float worstDeviation(const std::vector<glm::vec3>& ours, const std::vector<glm::vec3>& blender,
                     const std::vector<size_t>& map) {
  float worst = 0.0f;
  for (size_t i = 0; i < ours.size(); ++i) worst = std::max(worst, glm::length(ours[i] - blender[map[i]]));
  return worst;
}

// The character's unmorphed rest pose: its bind shape, where Blender's "rest" is.
std::vector<glm::vec3> restWithoutMorphs(Character c) {
  for (Mesh& m : c.meshes) m.morphTargets.clear(), m.defaultMorphWeights.clear();
  return skinnedWorldPositions(c, nullptr, 0.0f);
}

}  // namespace

TEST_CASE("blend shapes: a Khronos sample's morph targets and weight animation are read and played", "[io][blendshape]") {
  if (!std::filesystem::exists(kMorphCube)) ANIMORPH_SKIP(kMorphCube << " is not installed (Debian's assimp-testmodels)");
  auto c = importGltf(kMorphCube);
  REQUIRE(c.ok());
  REQUIRE(c->meshes.size() == 1);
  const Mesh& m = c->meshes[0];
  REQUIRE(m.morphTargets.size() == 2);
  CHECK(m.morphTargets[0].name == "target 0");  // the file names none
  CHECK(m.morphTargets[0].positionDeltas.size() == m.vertexCount());
  CHECK(m.morphTargets[1].normalDeltas.size() == m.vertexCount());
  CHECK(m.defaultMorphWeights == std::vector<float>{0.0f, 0.0f});
  REQUIRE(c->clips.size() == 1);
  const Channel& ch = c->clips[0].channels.at(0);
  CHECK(ch.path == ChannelPath::Weights);
  CHECK(ch.weightCount == 2);
  CHECK(ch.weightValues.size() == 2 * ch.timesSec.size());
  // The weights go through both targets over the clip and the vertices follow the deltas exactly.
  const int node = c->meshNodes().at(0);
  float most = 0.0f;
  for (float t = 0.0f; t <= c->clips[0].durationSec; t += 0.1f) {
    const auto w = morphWeightsAt(*c, node, &c->clips[0], t);
    REQUIRE(w.size() == 2);
    CHECK(w[0] >= -1e-6f);
    CHECK(w[0] <= 1.0f + 1e-6f);
    std::vector<glm::vec3> pos, nrm;
    skinMesh(m, {glm::mat4(1.0f)}, pos, nrm, w);
    for (size_t v = 0; v < m.vertexCount(); ++v) {
      const glm::vec3 expect = m.positions[v] + w[0] * m.morphTargets[0].positionDeltas[v] + w[1] * m.morphTargets[1].positionDeltas[v];
      REQUIRE(glm::length(pos[v] - expect) < 1e-6f);
      most = std::max(most, glm::length(pos[v] - m.positions[v]));
    }
  }
  CHECK(most > 0.1f * m.bounds().diagonal());  // the animation does move the cube
}

TEST_CASE("blend shapes: a mesh's primitives concatenate their targets, zero deltas where a primitive has none", "[io][blendshape]") {
  TempDir tmp;
  MiniGltf g;
  const int posA = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int posB = g.addFloats({2, 0, 0, 3, 0, 0, 2, 1, 0}, "VEC3");
  const int dA0 = g.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
  const int dA1 = g.addFloats({1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
  using json = nlohmann::json;
  g.json()["accessors"][posA]["min"] = std::vector<float>{0, 0, 0};
  g.json()["accessors"][posA]["max"] = std::vector<float>{1, 1, 0};
  g.json()["accessors"][posB]["min"] = std::vector<float>{2, 0, 0};
  g.json()["accessors"][posB]["max"] = std::vector<float>{3, 1, 0};
  json primA = json::object(), primB = json::object(), mesh = json::object(), node = json::object();
  primA["attributes"]["POSITION"] = posA;
  primA["targets"] = json::array();
  primA["targets"].push_back(json{{"POSITION", dA0}});
  primA["targets"].push_back(json{{"POSITION", dA1}});
  primB["attributes"]["POSITION"] = posB;
  mesh["primitives"] = json::array({primA, primB});
  mesh["weights"] = std::vector<double>{0.5, 0.25};
  mesh["extras"]["targetNames"] = std::vector<std::string>{"lift", "slide"};
  g.json()["meshes"] = json::array({mesh});
  node["mesh"] = 0;
  g.json()["nodes"] = json::array({node});
  auto c = importGltf(g.write(tmp.path().string(), "two_primitives.gltf"));
  INFO(c.error());
  REQUIRE(c.ok());
  const Mesh& m = c->meshes[0];
  REQUIRE(m.vertexCount() == 6);
  REQUIRE(m.morphTargets.size() == 2);
  CHECK(m.morphTargets[0].name == "lift");
  CHECK(m.morphTargets[1].name == "slide");
  CHECK(m.morphTargets[0].positionDeltas[2] == glm::vec3(0, 0, 1));
  CHECK(m.morphTargets[0].positionDeltas[3] == glm::vec3(0.0f));  // primitive B: none
  CHECK(m.morphTargets[1].positionDeltas[0] == glm::vec3(1, 0, 0));
  // No animation: the mesh's default weights shape it.
  const auto pos = skinnedWorldPositions(*c, nullptr, 0.0f);
  CHECK(glm::length(pos[0] - glm::vec3(0.25f, 0.0f, 0.5f)) < 1e-6f);
  CHECK(glm::length(pos[1] - glm::vec3(1.0f, 0.0f, 0.5f)) < 1e-6f);
  CHECK(pos[4] == glm::vec3(3, 0, 0));

  // A node's own weights replace the mesh's; a wrong count is refused, naming the node.
  g.json()["nodes"][0]["weights"] = std::vector<double>{0.0, 1.0};
  auto withNode = importGltf(g.write(tmp.path().string(), "node_weights.gltf"));
  REQUIRE(withNode.ok());
  CHECK(skinnedWorldPositions(*withNode, nullptr, 0.0f)[0] == glm::vec3(1, 0, 0));
  g.json()["nodes"][0]["weights"] = std::vector<double>{1.0};
  auto bad = importGltf(g.write(tmp.path().string(), "bad_weights.gltf"));
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error() == tmp.file("bad_weights.gltf") + ": node 0: 1 weights for the 2 morph targets of its mesh");
}

TEST_CASE("blend shapes: CUBICSPLINE weight keys follow glTF's Hermite form, STEP holds", "[rig][blendshape]") {
  Character c;
  c.nodes.push_back({"m", -1, {}, {}, 0, -1});
  c.roots = {0};
  Mesh m;
  m.positions = {glm::vec3(0.0f)};
  m.normals = {glm::vec3(0, 1, 0)};
  m.morphTargets = {{"a", {glm::vec3(1, 0, 0)}, {}}, {"b", {glm::vec3(0, 1, 0)}, {}}};
  c.meshes.push_back(m);
  AnimationClip clip;
  Channel ch;
  ch.node = 0;
  ch.path = ChannelPath::Weights;
  ch.interpolation = Interpolation::CubicSpline;
  ch.timesSec = {0.0f, 2.0f};
  ch.weightCount = 2;
  // Per key: in-tangents (a, b), values (a, b), out-tangents (a, b).
  ch.weightValues = {0, 0, 0.0f, 1.0f, 0.5f, 0.0f, /* key 1 */ -0.25f, 0.0f, 1.0f, 0.0f, 0, 0};
  clip.channels.push_back(ch);
  clip.durationSec = 2.0f;
  const auto w = morphWeightsAt(c, 0, &clip, 1.0f);
  // u = 0.5, dt = 2: h00 = h01 = 0.5, h10 = 0.125, h11 = -0.125.
  REQUIRE(w.size() == 2);
  CHECK(w[0] == Approx(0.5f * 0.0f + 0.125f * 0.5f * 2.0f + 0.5f * 1.0f + -0.125f * -0.25f * 2.0f));
  CHECK(w[1] == Approx(0.5f));
  CHECK(morphWeightsAt(c, 0, &clip, 2.0f)[0] == Approx(1.0f));
  clip.channels[0].interpolation = Interpolation::Step;
  clip.channels[0].weightValues = {0.25f, 0.5f, 1.0f, 0.0f};
  CHECK(morphWeightsAt(c, 0, &clip, 1.9f) == std::vector<float>{0.25f, 0.5f});
  CHECK(skinnedWorldPositions(c, &clip, 1.9f)[0] == glm::vec3(0.25f, 0.5f, 0.0f));
}

// Hidden from the plain run: registered with the Blender fixture (tests/CMakeLists.txt).
TEST_CASE("blend shapes: Blender's weight animation moves the vertices as Blender evaluates them", "[.bs-blender-weights]") {
  const std::string dir = blenderDir();
  if (dir.empty()) ANIMORPH_SKIP("no Blender blend-shape character (Blender is not installed, or its fixture did not run)");
  const BlenderReference ref = readReference(dir);
  auto c = importGltf(dir + "/blend_shape_character.glb");
  INFO(c.error());
  REQUIRE(c.ok());
  CHECK(c->report.unsupported.empty());
  REQUIRE(c->meshes.size() == 1);
  REQUIRE(c->meshes[0].morphTargets.size() == 2);
  CHECK(c->meshes[0].morphTargets[0].name == "bulge");
  CHECK(c->meshes[0].morphTargets[1].name == "lean");
  REQUIRE(c->clips.size() == 1);
  const auto map = matchVertices(restWithoutMorphs(*c), ref.rest);
  const float diag = diagonal(ref.rest);
  Character noMorph = *c;
  for (Mesh& m : noMorph.meshes) m.morphTargets.clear();
  for (const auto& [frame, blender] : ref.frames) {
    const float t = float(frame / ref.fps);
    const auto ours = skinnedWorldPositions(*c, &c->clips[0], t);
    INFO("frame " << frame);
    REQUIRE(ours.size() == map.size());
    CHECK(worstDeviation(ours, blender, map) <= 1e-4f * diag);
    // The shapes matter: without them the same pose is far from Blender's (except where the weights are 0).
    const auto w = morphWeightsAt(*c, c->meshNodes()[0], &c->clips[0], t);
    if (hasActiveMorph(w) && w[0] > 0.1f) CHECK(worstDeviation(skinnedWorldPositions(noMorph, &c->clips[0], t), blender, map) > 0.02f * diag);
  }
}

TEST_CASE("blend shapes: default weights shape the mesh with no animation, as in Blender", "[.bs-blender-defaults]") {
  const std::string dir = blenderDir();
  if (dir.empty()) ANIMORPH_SKIP("no Blender blend-shape character (Blender is not installed, or its fixture did not run)");
  const BlenderReference ref = readReference(dir);
  auto c = importGltf(dir + "/blend_shape_static.glb");
  INFO(c.error());
  REQUIRE(c.ok());
  CHECK(c->clips.empty());
  REQUIRE(c->meshes.size() == 1);
  CHECK(c->meshes[0].defaultMorphWeights == std::vector<float>{0.5f, 0.25f});
  const auto map = matchVertices(restWithoutMorphs(*c), ref.rest);
  const float diag = diagonal(ref.rest);
  CHECK(worstDeviation(skinnedWorldPositions(*c, nullptr, 0.0f), ref.stat, map) <= 1e-4f * diag);
  CHECK(worstDeviation(restWithoutMorphs(*c), ref.stat, map) > 0.02f * diag);  // the defaults do move it
}

namespace {

std::vector<glm::vec3> scaled(std::vector<glm::vec3> pts, double metresPerUnit) {
  for (glm::vec3& p : pts) p *= float(metresPerUnit);
  return pts;
}

// Blender's static scene through another exporter (FBX, Collada): both shapes at the values they
// were held at (0.5, 0.25) with no animation, and the character at rest where Blender puts it.
void checkStaticShapes(const Character& c, const BlenderReference& ref) {
  REQUIRE(c.meshes.size() == 1);
  REQUIRE(c.meshes[0].morphTargets.size() == 2);
  CHECK(c.meshes[0].morphTargets[0].name == "bulge");
  CHECK(c.meshes[0].morphTargets[1].name == "lean");
  CHECK(c.meshes[0].defaultMorphWeights == std::vector<float>{0.5f, 0.25f});
  CHECK(c.skins.size() == 1);
  const double mpu = c.unit.metresPerUnit;
  const auto map = matchVertices(scaled(restWithoutMorphs(c), mpu), ref.rest);
  const float diag = diagonal(ref.rest);
  const float worst = worstDeviation(scaled(skinnedWorldPositions(c, nullptr, 0.0f), mpu), ref.stat, map);
  CHECK(worst <= 1e-4f * diag);
  CHECK(worstDeviation(scaled(restWithoutMorphs(c), mpu), ref.stat, map) > 0.02f * diag);  // the values do move it
  WARN(c.format << " shapes at their values: worst deviation from Blender " << worst / diag << " of the diagonal");
}

}  // namespace

TEST_CASE("blend shapes: Blender's FBX plays its shape keys and their animation as Blender evaluates them",
          "[.bs-blender-fbx]") {
  const std::string dir = blenderDir();
  if (dir.empty()) ANIMORPH_SKIP("no Blender blend-shape character (Blender is not installed, or its fixture did not run)");
  const BlenderReference ref = readReference(dir);
  auto c = importAssimp(dir + "/blend_shape_character.fbx");
  INFO(c.error());
  REQUIRE(c.ok());
  CHECK(c->report.unsupported.empty());
  REQUIRE(c->meshes.size() == 1);
  REQUIRE(c->meshes[0].morphTargets.size() == 2);
  CHECK(c->meshes[0].morphTargets[0].name == "bulge");
  CHECK(c->meshes[0].morphTargets[1].name == "lean");
  REQUIRE_FALSE(c->clips.empty());
  const AnimationClip& clip = c->clips[0];
  const auto weights = std::find_if(clip.channels.begin(), clip.channels.end(),
                                    [](const Channel& ch) { return ch.path == ChannelPath::Weights; });
  REQUIRE(weights != clip.channels.end());
  CHECK(weights->weightCount == 2);
  const double mpu = c->unit.metresPerUnit;
  // The FBX's node rest transforms are the pose Blender exported from, not the bind pose: the
  // vertices are matched at the first reference frame instead (no shape is keyed above 0 there).
  const auto& [firstFrame, firstPose] = *ref.frames.begin();
  const auto map = matchVertices(scaled(skinnedWorldPositions(*c, &clip, float(firstFrame / ref.fps)), mpu), firstPose);
  const float diag = diagonal(ref.rest);
  Character noMorph = *c;
  for (Mesh& m : noMorph.meshes) m.morphTargets.clear();
  float worst = 0.0f;
  for (const auto& [frame, blender] : ref.frames) {
    const float t = float(frame / ref.fps);
    const auto ours = scaled(skinnedWorldPositions(*c, &clip, t), mpu);
    INFO("frame " << frame);
    REQUIRE(ours.size() == map.size());
    worst = std::max(worst, worstDeviation(ours, blender, map));
    CHECK(worstDeviation(ours, blender, map) <= 1e-4f * diag);
    const auto w = morphWeightsAt(*c, c->meshNodes()[0], &clip, t);
    if (hasActiveMorph(w) && w[0] > 0.1f)
      CHECK(worstDeviation(scaled(skinnedWorldPositions(noMorph, &clip, t), mpu), blender, map) > 0.02f * diag);
  }
  WARN("FBX blend shapes: worst deviation from Blender " << worst / diag << " of the diagonal");

  // The static file: its channels' values (DeformPercent 50 and 25, read beside assimp) are the
  // shapes' weights, and nothing says they are missing.
  auto st = importAssimp(dir + "/blend_shape_static.fbx");
  INFO(st.error());
  REQUIRE(st.ok());
  checkStaticShapes(*st, ref);
  const bool missing = std::any_of(st->report.warnings.begin(), st->report.warnings.end(), [](const std::string& w) {
    return w.find("no value in the file") != std::string::npos;
  });
  CHECK_FALSE(missing);
}

TEST_CASE("blend shapes: Blender's Collada with a skin and shape keys opens with its shapes at their values, "
          "as Blender evaluates them",
          "[.bs-blender-dae]") {
  const std::string dir = blenderDir();
  if (dir.empty()) ANIMORPH_SKIP("no Blender blend-shape character (Blender is not installed, or its fixture did not run)");
  const BlenderReference ref = readReference(dir);
  auto st = importAssimp(dir + "/blend_shape_static.dae");
  INFO(st.error());
  REQUIRE(st.ok());
  checkStaticShapes(*st, ref);
  // The animated scene: its shapes hold the values of the frame Blender exported at (24: bulge 0.2,
  // lean 0.6). Blender's Collada writes no shape animation, and none of the actions this scene
  // keeps on NLA tracks (no active action): the file has no clip.
  auto an = importAssimp(dir + "/blend_shape_character.dae");
  INFO(an.error());
  REQUIRE(an.ok());
  REQUIRE(an->meshes.size() == 1);
  REQUIRE(an->meshes[0].morphTargets.size() == 2);
  CHECK(an->meshes[0].defaultMorphWeights.at(0) == Approx(0.2).margin(1e-4));
  CHECK(an->meshes[0].defaultMorphWeights.at(1) == Approx(0.6).margin(1e-4));
  CHECK(an->skins.size() == 1);
}

TEST_CASE("blend shapes: an exported character keeps its targets and weight animation (round trip)", "[.bs-blender-export]") {
  const std::string dir = blenderDir();
  if (dir.empty()) ANIMORPH_SKIP("no Blender blend-shape character (Blender is not installed, or its fixture did not run)");
  auto c = importGltf(dir + "/blend_shape_character.glb");
  REQUIRE(c.ok());
  // Written beside the fixture's files for the glTF-Validator test (cli/blend_shape_checks.py).
  const std::string out = dir + "/reexported.glb";
  REQUIRE(exportGlb(*c, out).ok());
  auto back = importGltf(out);
  INFO(back.error());
  REQUIRE(back.ok());
  CHECK(back->report.warnings.empty());
  REQUIRE(back->meshes.at(0).morphTargets.size() == 2);
  CHECK(back->meshes[0].morphTargets[1].name == "lean");
  const float diag = diagonal(skinnedWorldPositions(*c, nullptr, 0.0f));
  for (float t = 0.0f; t <= c->clips[0].durationSec; t += 1.0f / 24.0f) {
    const auto a = skinnedWorldPositions(*c, &c->clips[0], t), b = skinnedWorldPositions(*back, &back->clips[0], t);
    REQUIRE(a.size() == b.size());
    float worst = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
    INFO("t = " << t);
    CHECK(worst <= 1e-6f * diag);
  }
}

TEST_CASE("blend shapes: a bake of a morph from a character with blend shapes carries their motion", "[.bs-blender-bake]") {
  const std::string dir = blenderDir();
  if (dir.empty()) ANIMORPH_SKIP("no Blender blend-shape character (Blender is not installed, or its fixture did not run)");
  const BlenderReference ref = readReference(dir);
  TempDir tmp;
  std::filesystem::copy_file(dir + "/blend_shape_character.glb", tmp.file("tube.glb"));
  REQUIRE(exportGlb(test::demoGear(), tmp.file("gear.glb")).ok());
  auto tube = importGltf(tmp.file("tube.glb"));
  REQUIRE(tube.ok());
  NewMorphSettings ns;
  ns.acceptPoorFit = true;  // the fit is not what this test is about
  auto made = makeMorphProject(*tube, "tube.glb", test::demoGear(), "gear.glb", ns);
  INFO(made.error());
  REQUIRE(made.ok());
  auto frames = ProjectFrames::prepare(made->project, tmp.path().string());
  INFO(frames.error());
  REQUIRE(frames.ok());
  const auto map = matchVertices(restWithoutMorphs(*tube), ref.rest);
  const float diag = diagonal(ref.rest);
  const Actor* src = nullptr;
  for (const Actor& a : made->project.actors)
    if (a.id == made->project.morph.sourceActorId) src = &a;
  REQUIRE(src);
  REQUIRE(src->transform.matrix() == glm::mat4(1.0f));  // the source stays where Blender put it
  // Frames before marker A show the source playing its clip: Blender's evaluated mesh, shapes and all.
  for (int frame : {5, 10, 15, 20}) {
    REQUIRE(frame < made->project.morph.markers.a);
    FrameBakeSettings fs;
    fs.resolution = 16;
    auto baked = frames->frame(frame, fs);
    INFO("frame " << frame << ": " << baked.error());
    REQUIRE(baked.ok());
    REQUIRE(baked->mesh.positions.size() == map.size());
    CHECK(worstDeviation(baked->mesh.positions, ref.frames.at(frame), map) <= 1e-4f * diag);
  }
}

TEST_CASE("blend shapes: transitions start from the morphed mesh and still end on the stand-in", "[morph][blendshape]") {
  // The demo creature with one made-up target on its first mesh, moving every vertex by 0.1 m.
  const Character plain = test::demoCreature();
  Character c = plain;
  const int node = c.meshNodes().at(0);
  Mesh& mesh = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
  mesh.morphTargets = {{"shift", std::vector<glm::vec3>(mesh.vertexCount(), glm::vec3(0.0f, 0.1f, 0.0f)), {}}};
  mesh.defaultMorphWeights = {1.0f};
  const Standin& standin = test::demoMorph().runtime->source.morph.standin;
  const auto globals = poseGlobals(c, nullptr, 0.0f);
  const auto segs = poseStandin(standin, globals, glm::mat4(1.0f));
  const FieldProgram field = standinProgram(standin.kind, standin.sharpness, segs);
  TransitionSettings ts;
  ts.reprojectFrom = 1.0f;  // no re-projection: the binding alone
  for (int k : c.meshNodes()) ts.morphWeights.push_back(morphWeightsAt(c, k, nullptr, 0.0f));
  // The worst |field| over the vertices at alpha = 1 (0 on the stand-in's surface).
  auto worstOffSurface = [&](const Character& ch, const TransitionSettings& settings) {
    const StandinBinding b = bindToStandin(ch, standin, nullptr, 0.0f, ProjectionSettings{});
    std::vector<glm::vec3> pos, nrm;
    evaluateTransition(ch, b, globals, glm::mat4(1.0f), std::vector<float>(b.offsets.size(), 1.0f), nullptr, nullptr,
                       settings, pos, nrm);
    float worst = 0.0f;
    for (const auto& p : pos) worst = std::max(worst, std::abs(test::fieldAt(field, p)));
    return worst;
  };
  const float baseline = worstOffSurface(plain, TransitionSettings{});
  CHECK(worstOffSurface(c, ts) <= 2.0f * baseline + 1e-4f);
  // alpha = 0: the skinned, morphed mesh, 0.1 m from the unmorphed one.
  const StandinBinding binding = bindToStandin(c, standin, nullptr, 0.0f, ProjectionSettings{});
  const size_t n = binding.offsets.size();
  std::vector<glm::vec3> pos0, nrm0, flat0, flatN;
  evaluateTransition(c, binding, globals, glm::mat4(1.0f), std::vector<float>(n, 0.0f), nullptr, nullptr, ts, pos0, nrm0);
  const auto skinned = skinnedWorldPositions(c, nullptr, 0.0f);
  REQUIRE(skinned.size() == n);
  float worst0 = 0.0f;
  for (size_t i = 0; i < n; ++i) worst0 = std::max(worst0, glm::length(pos0[i] - skinned[i]));
  CHECK(worst0 < 1e-5f);
  evaluateTransition(c, binding, globals, glm::mat4(1.0f), std::vector<float>(n, 0.0f), nullptr, nullptr,
                     TransitionSettings{}, flat0, flatN);
  CHECK(glm::length(pos0[0] - flat0[0]) > 0.05f);
}

TEST_CASE("blend shapes: malformed targets are refused naming the file, the element and the reason", "[io][blendshape]") {
  TempDir tmp;
  MiniGltf g;
  const int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int shortDelta = g.addFloats({0, 0, 1, 0, 0, 1}, "VEC3");
  using json = nlohmann::json;
  g.json()["accessors"][pos]["min"] = std::vector<float>{0, 0, 0};
  g.json()["accessors"][pos]["max"] = std::vector<float>{1, 1, 0};
  json prim = json::object(), mesh = json::object(), node = json::object();
  prim["attributes"]["POSITION"] = pos;
  prim["targets"] = json::array({json{{"POSITION", shortDelta}}});
  mesh["primitives"] = json::array({prim});
  g.json()["meshes"] = json::array({mesh});
  node["mesh"] = 0;
  g.json()["nodes"] = json::array({node});
  auto c = importGltf(g.write(tmp.path().string(), "short.gltf"));
  REQUIRE_FALSE(c.ok());
  CHECK(c.error() == tmp.file("short.gltf") +
                         ": mesh 0 primitive 0 morph target 0: morph target POSITION has 2 elements but POSITION has 3");
  g.json()["meshes"][0]["primitives"][0]["targets"] = json::array({json{{"TEXCOORD_0", pos}}});
  auto odd = importGltf(g.write(tmp.path().string(), "odd.gltf"));
  REQUIRE_FALSE(odd.ok());
  CHECK(odd.error() == tmp.file("odd.gltf") +
                           ": mesh 0 primitive 0 morph target 0: attribute 'TEXCOORD_0' cannot be a morph target "
                           "(POSITION, NORMAL or TANGENT)");
}
