#include <catch2/catch.hpp>

#include <map>

#include "demo/creature.h"
#include "demo/dense.h"
#include "demo/gear.h"
#include "core/io/gltf_export.h"
#include "core/io/gltf_import.h"
#include "core/rig/pose.h"
#include "core/rig/skinning.h"
#include "util/temp_dir.h"

using namespace animorph;
using animorph::test::TempDir;

namespace {

// Index of the first element where a and b differ (by more than tol), or -1.
template <class V>
long firstMismatch(const std::vector<V>& a, const std::vector<V>& b, float tol = 0.0f) {
  if (a.size() != b.size()) return -2;
  for (size_t i = 0; i < a.size(); ++i)
    if (glm::any(glm::greaterThan(glm::abs(glm::vec<V::length(), float>(a[i]) - glm::vec<V::length(), float>(b[i])),
                                  glm::vec<V::length(), float>(tol))))
      return static_cast<long>(i);
  return -1;
}

// Weight of each joint over both influence sets of vertex v.
std::map<uint32_t, float> influences(const Mesh& m, size_t v) {
  std::map<uint32_t, float> out;
  for (int k = 0; k < 4; ++k) {
    if (m.weights0[v][k] > 0.0f) out[m.joints0[v][k]] += m.weights0[v][k];
    if (!m.weights1.empty() && m.weights1[v][k] > 0.0f) out[m.joints1[v][k]] += m.weights1[v][k];
  }
  return out;
}

// Exports c, imports the file back and compares everything glTF can carry.
void checkRoundTrip(const Character& c) {
  TempDir tmp;
  const std::string path = tmp.file("roundtrip.glb");
  REQUIRE(exportGlb(c, path).ok());
  auto back = importGltf(path);
  REQUIRE(back.ok());
  const Character& r = *back;
  CHECK(r.report.warnings.empty());
  CHECK(r.report.weightsNormalised == 0);
  REQUIRE(r.nodes.size() == c.nodes.size());
  CHECK(r.roots == c.roots);
  for (size_t i = 0; i < c.nodes.size(); ++i) {
    CHECK(r.nodes[i].name == c.nodes[i].name);
    CHECK(r.nodes[i].parent == c.nodes[i].parent);
    CHECK(r.nodes[i].mesh == c.nodes[i].mesh);
    CHECK(r.nodes[i].skin == c.nodes[i].skin);
    CHECK(r.nodes[i].rest == c.nodes[i].rest);
  }
  REQUIRE(r.meshes.size() == c.meshes.size());
  for (size_t m = 0; m < c.meshes.size(); ++m) {
    CHECK(firstMismatch(r.meshes[m].positions, c.meshes[m].positions) == -1);
    CHECK(r.meshes[m].indices == c.meshes[m].indices);
    CHECK(firstMismatch(r.meshes[m].normals, c.meshes[m].normals, 1e-5f) == -1);
    CHECK(r.meshes[m].joints1.empty() == c.meshes[m].joints1.empty());
    // The importer orders influences by weight; compare them as joint -> weight.
    long badVertex = -1;
    for (size_t v = 0; v < c.meshes[m].vertexCount() && badVertex < 0; ++v) {
      auto a = influences(r.meshes[m], v), b = influences(c.meshes[m], v);
      bool same = a.size() == b.size();
      for (const auto& [j, w] : b) same = same && a.count(j) && std::abs(a[j] - w) < 1e-6f;
      if (!same) badVertex = static_cast<long>(v);
    }
    CHECK(badVertex == -1);
  }
  REQUIRE(r.skins.size() == c.skins.size());
  for (size_t s = 0; s < c.skins.size(); ++s) {
    CHECK(r.skins[s].joints == c.skins[s].joints);
    CHECK(r.skins[s].inverseBindMatrices == c.skins[s].inverseBindMatrices);
  }
  REQUIRE(r.clips.size() == c.clips.size());
  for (size_t a = 0; a < c.clips.size(); ++a) {
    CHECK(r.clips[a].name == c.clips[a].name);
    CHECK(r.clips[a].durationSec == c.clips[a].durationSec);
    REQUIRE(r.clips[a].channels.size() == c.clips[a].channels.size());
    for (size_t k = 0; k < c.clips[a].channels.size(); ++k) {
      const auto& x = r.clips[a].channels[k];
      const auto& y = c.clips[a].channels[k];
      CHECK(x.node == y.node);
      CHECK(x.path == y.path);
      CHECK(x.interpolation == y.interpolation);
      CHECK(x.timesSec == y.timesSec);
      REQUIRE(x.values.size() == y.values.size());
      for (size_t i = 0; i < x.values.size(); ++i) {
        glm::vec4 a4 = x.values[i], b4 = y.values[i];
        if (y.path != ChannelPath::Rotation) { a4.w = b4.w = 0.0f; }
        CHECK(a4 == b4);
      }
    }
    // Same animated surface.
    const float t = 0.37f * c.clips[a].durationSec;
    auto p = skinnedWorldPositions(c, &c.clips[a], t), q = skinnedWorldPositions(r, &r.clips[a], t);
    REQUIRE(p.size() == q.size());
    float worst = 0.0f;
    for (size_t i = 0; i < p.size(); ++i) worst = std::max(worst, glm::length(p[i] - q[i]));
    CHECK(worst < 1e-5f);
  }
}

}  // namespace

TEST_CASE("export -> import round-trips the demo characters", "[io][gltf][export]") {
  checkRoundTrip(makeCreatureCharacter());
  checkRoundTrip(makeGearCharacter());
  checkRoundTrip(makeDenseCharacter(2000));
}

TEST_CASE("export -> import round-trips STEP and CUBICSPLINE channels and a second influence set", "[io][gltf][export]") {
  Character c = makeDenseCharacter(500);
  Mesh& m = c.meshes[0];
  m.joints1.assign(m.vertexCount(), glm::uvec4(0));
  m.weights1.assign(m.vertexCount(), glm::vec4(0.0f));
  // Vertex 0 spreads over six joints: 0.25 x 2, then 0.125 x 4.
  m.joints0[0] = {0, 1, 2, 3};
  m.weights0[0] = {0.25f, 0.25f, 0.125f, 0.125f};
  m.joints1[0] = {4, 5, 0, 0};
  m.weights1[0] = {0.125f, 0.125f, 0, 0};
  Channel step;
  step.node = c.skins[0].joints[2];
  step.path = ChannelPath::Translation;
  step.interpolation = Interpolation::Step;
  step.timesSec = {0.0f, 0.5f, 1.0f};
  step.values = {{0.25f, 0, 0, 0}, {0.25f, 0.1f, 0, 0}, {0.25f, 0, 0, 0}};
  Channel cubic = step;
  cubic.path = ChannelPath::Scale;
  cubic.interpolation = Interpolation::CubicSpline;
  cubic.timesSec = {0.0f, 1.0f};
  cubic.values = {{0, 0, 0, 0}, {1, 1, 1, 0}, {0.5f, 0, 0, 0}, {0, 0, 0, 0}, {2, 1, 1, 0}, {0, 0, 0, 0}};
  c.clips[0].channels.push_back(step);
  c.clips[0].channels.push_back(cubic);
  checkRoundTrip(c);
}

TEST_CASE("export refuses data glTF cannot hold", "[io][gltf][export]") {
  Character c = makeDenseCharacter(500);
  c.meshes[0].indices[4] = 999999;
  auto r = exportGlbBytes(c);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().find("index 999999 out of range") != std::string::npos);
  c = makeDenseCharacter(500);
  c.clips[0].channels[0].timesSec[2] = c.clips[0].channels[0].timesSec[1];
  r = exportGlbBytes(c);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().find("key times must increase (key 2)") != std::string::npos);
}
