// Colour through the morph (docs/morph.md, "Colour through the morph"): the stand-in's colour
// profiles sampled from the character, the colour program's field, the transitions' colours and
// the implicit stage's.
#include <algorithm>
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "core/field/surface_color.h"
#include "core/io/gltf_export.h"
#include "core/math/color.h"
#include "core/poly/polygonizer.h"
#include "core/rig/vertex_colors.h"
#include "core/scene/morph_runtime.h"
#include "core/standin/character_pose.h"
#include "core/standin/standin_colors.h"
#include "util/morph_fixtures.h"
#include "util/temp_dir.h"

using namespace animorph;

namespace {

const glm::vec4 kRed{0.9f, 0.05f, 0.05f, 1.0f}, kBlue{0.05f, 0.1f, 0.9f, 1.0f};

// The demo creature without materials, its vertices red on one side of the plane through its
// rest centre across `axis`, blue on the other.
Character twoColouredCreature(int axis, float centre) {
  Character c = test::demoCreature();
  c.materials.clear();
  c.textures.clear();
  const CharacterPose pose = poseCharacter(c, nullptr, 0.0f, glm::mat4(1.0f));
  size_t v = 0;
  for (int node : c.meshNodes()) {
    Mesh& m = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
    m.material = -1;
    for (Mesh::Part& p : m.parts) p.material = -1;
    m.colors.resize(m.vertexCount());
    for (glm::vec4& col : m.colors) col = pose.positions[v++][axis] > centre ? kRed : kBlue;
  }
  return c;
}

}  // namespace

TEST_CASE("stand-in colours: a character's vertex colour is its material factor x texture x COLOR_0", "[color][morph]") {
  Character c;
  Mesh m;
  m.positions = {glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};
  m.indices = {0, 1, 2};
  m.texcoords0 = {glm::vec2(0.5f), glm::vec2(0.5f), glm::vec2(0.5f)};
  m.colors = {glm::vec4(0.5f, 1, 1, 1), glm::vec4(1), glm::vec4(1, 1, 0.25f, 1)};
  m.material = 0;
  c.meshes.push_back(m);
  Node n;
  n.mesh = 0;
  c.nodes.push_back(n);
  c.roots = {0};
  Material mat;
  mat.baseColorFactor = glm::vec4(0.5f, 0.25f, 1.0f, 1.0f);
  mat.baseColorTexture = 0;
  c.materials.push_back(mat);
  TextureImage tex;
  tex.width = tex.height = 1;
  tex.rgba = std::make_shared<const std::vector<uint8_t>>(std::vector<uint8_t>{128, 255, 64, 255});
  c.textures.push_back(tex);
  const std::vector<glm::vec4> out = characterVertexColors(c);
  REQUIRE(out.size() == 3);
  const glm::vec3 texel = srgbToLinear(glm::vec3(128, 255, 64) / 255.0f);
  const glm::vec3 want0 = glm::vec3(0.5f, 0.25f, 1.0f) * texel * glm::vec3(0.5f, 1, 1);
  const glm::vec3 want2 = glm::vec3(0.5f, 0.25f, 1.0f) * texel * glm::vec3(1, 1, 0.25f);
  for (int k = 0; k < 3; ++k) {
    CHECK(out[0][k] == Approx(want0[k]).margin(1e-6));
    CHECK(out[2][k] == Approx(want2[k]).margin(1e-6));
  }
  // No colour of its own anywhere: none (its stand-in keeps the clay tone).
  c.materials.clear();
  c.textures.clear();
  c.meshes[0].colors.clear();
  CHECK(characterVertexColors(c).empty());
}

TEST_CASE("stand-in colours: the segments of a two-coloured character take the colour of their side", "[color][morph]") {
  const Character& plain = test::demoCreature();
  const Project& demo = test::demoMorph().project;
  const Standin& standin = demo.morph.findActor(demo.morph.sourceActorId)->standin;
  const CharacterPose pose = poseCharacter(plain, nullptr, 0.0f, glm::mat4(1.0f));
  const std::vector<PosedSegment> segs = poseStandin(standin, pose.globals, glm::mat4(1.0f));
  Bounds box;
  for (const glm::vec3& p : pose.positions) box.add(p);
  const float margin = 0.03f * box.diagonal();
  // The axis across which segments lie on both sides (the creature's legs).
  int axis = -1;
  float centre = 0.0f;
  for (int k : {0, 2, 1}) {
    const float c = 0.5f * (box.min[k] + box.max[k]);
    int above = 0, below = 0;
    for (const PosedSegment& s : segs) {
      above += std::min(s.a[k], s.b[k]) - s.radius > c + margin;
      below += std::max(s.a[k], s.b[k]) + s.radius < c - margin;
    }
    if (above > 0 && below > 0) {
      axis = k, centre = c;
      break;
    }
  }
  REQUIRE(axis >= 0);
  const Character c = twoColouredCreature(axis, centre);
  const StandinBinding b = bindToStandin(c, standin, nullptr, 0.0f, ProjectionSettings{});
  REQUIRE(b.hasColors());
  REQUIRE(b.segmentColors.size() == segs.size());
  int red = 0, blue = 0;
  for (size_t i = 0; i < segs.size(); ++i) {
    const PosedSegment& s = segs[i];
    const bool above = std::min(s.a[axis], s.b[axis]) - s.radius > centre + margin;
    const bool below = std::max(s.a[axis], s.b[axis]) + s.radius < centre - margin;
    if (!above && !below) continue;
    INFO("segment " << i << " on the " << (above ? "red" : "blue") << " side");
    for (const glm::vec3& sample : b.segmentColors[i].samples) {
      CHECK(glm::distance(sample, glm::vec3(above ? kRed : kBlue)) < 1e-4f);
      (above ? red : blue) += 1;
    }
  }
  CHECK(red > 0);
  CHECK(blue > 0);
  // The stand-in's colour where each vertex lands leans to its own side's, away from the middle
  // (the Cauchy kernel reaches far: the other side's segments weigh in near the body).
  size_t far = 0, same = 0;
  for (size_t v = 0; v < pose.positions.size(); ++v) {
    if (std::abs(pose.positions[v][axis] - centre) < 2.0f * margin) continue;
    ++far;
    const bool above = pose.positions[v][axis] > centre;
    const glm::vec3 c(b.standinColors[v]);
    same += glm::distance(c, glm::vec3(above ? kRed : kBlue)) < glm::distance(c, glm::vec3(above ? kBlue : kRed));
  }
  INFO(same << " of " << far << " vertices away from the middle land on their own side's colour (axis " << axis << ")");
  REQUIRE(far > 100);
  CHECK(double(same) / double(far) > 0.9);
}

TEST_CASE("stand-in colours: the colour program has the stand-in's field, its colours varying along a segment",
          "[color][morph]") {
  PosedSegment s;
  s.a = glm::vec3(0.0f);
  s.b = glm::vec3(1.0f, 0.0f, 0.0f);
  s.radius = 0.12f;
  s.colors.set = true;
  s.colors.samples = {glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
  PosedSegment t = s;
  t.a = glm::vec3(0.0f, 0.5f, 0.0f);
  t.b = glm::vec3(0.0f, 0.5f, 0.8f);
  t.weightScale = 0.6f;
  const std::vector<PosedSegment> segs{s, t};
  const std::vector<PosedSegment> split = splitSegmentsForColor(segs);
  REQUIRE(split.size() == 2 * kSegmentColorSamples);
  for (StandinKind kind : {StandinKind::Convolution, StandinKind::CapsuleUnion}) {
    const FieldProgram whole = standinProgram(kind, 20.0f, segs);
    const FieldProgram parts = standinProgram(kind, 20.0f, split);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-0.3f, 1.3f);
    for (int i = 0; i < 200; ++i) {
      const glm::vec3 x(u(rng), u(rng) * 0.8f, u(rng) * 0.8f);
      INFO("kind " << int(kind) << " at " << x.x << " " << x.y << " " << x.z);
      // Each part is cut where its own contribution falls under kStandinCutoffEpsilon T (standin.h).
      CHECK(test::fieldAt(parts, x) == Approx(test::fieldAt(whole, x)).margin(kSegmentColorSamples * kStandinCutoffEpsilon + 1e-4));
    }
  }
  // One primitive per segment: its mean colour; split: each end takes its own sample.
  const FieldProgram whole = standinProgram(StandinKind::Convolution, 20.0f, segs);
  const FieldProgram parts = standinProgram(StandinKind::Convolution, 20.0f, split);
  SurfaceColorEvaluator ev;
  const glm::vec3 nearA(0.02f, -0.12f, 0.0f), nearB(0.98f, -0.12f, 0.0f);
  CHECK(glm::distance(ev.evaluatePoint(whole, nearA), s.colors.mean()) < 1e-3f);
  CHECK(ev.evaluatePoint(parts, nearA).r > 0.8f);
  CHECK(ev.evaluatePoint(parts, nearA).b < 0.1f);
  CHECK(ev.evaluatePoint(parts, nearB).b > 0.8f);
  CHECK(ev.evaluatePoint(parts, nearB).r < 0.1f);
}

namespace {

// The demo morph with the two-coloured creature as its source (the gear keeps its bronze).
const MorphRuntime& colouredDemo() {
  static test::TempDir dir;
  static const std::shared_ptr<const MorphRuntime> rt = [] {
    const Project& p = test::demoMorph().project;
    REQUIRE(exportGlb(twoColouredCreature(0, 0.0f), dir.file("creature.glb")).ok());
    REQUIRE(exportGlb(test::demoGear(), dir.file("gear.glb")).ok());
    AssetCache assets;
    auto r = prepareMorph(p, dir.path().string(), assets);
    REQUIRE(r.ok());
    return *r;
  }();
  return *rt;
}

}  // namespace

TEST_CASE("transition colours: a vertex has its textured colour at alpha 0 and the stand-in's at alpha 1 (CPU)",
          "[color][morph]") {
  const MorphRuntime& rt = colouredDemo();
  const StandinBinding& b = rt.source.binding;
  REQUIRE(b.hasColors());
  REQUIRE(rt.target.binding.hasColors());  // the gear's bronze
  const double fps = rt.timeline.fps;
  const MorphMarkers& mk = rt.setup.markers;
  MorphFrameSettings s;
  s.reproject = false;
  for (double u : {0.0, 0.5, 1.0}) {
    const MorphFrame fr = evaluateMorphTransition(rt, mk.a / fps + u * (mk.b - mk.a) / fps, false, u, s);
    REQUIRE(fr.mesh.colors.size() == b.vertexColors.size());
    std::vector<float> alpha;
    transitionAlphas(u, rt.setup.easing, rt.source.morph.weightMap, rt.setup.weightMapShift, false, rt.source.vertexCount,
                     alpha);
    size_t off = 0;
    for (size_t v = 0; v < b.vertexColors.size(); v += 7) {
      const glm::vec4 want = u == 0.0 ? b.vertexColors[v] : u == 1.0 ? b.standinColors[v]
                                                          : glm::mix(b.vertexColors[v], b.standinColors[v], alpha[v]);
      off += glm::distance(fr.mesh.colors[v], want) > 1e-6f;
    }
    INFO("u = " << u);
    CHECK(off == 0);
  }
  // The stand-in colour is not the textured one (else the test shows nothing): the red and blue
  // sides meet in the middle of the stand-in.
  size_t differ = 0;
  for (size_t v = 0; v < b.vertexColors.size(); ++v) differ += glm::distance(b.vertexColors[v], b.standinColors[v]) > 0.05f;
  CHECK(differ > 0);
}

TEST_CASE("morph colours: the implicit stage at B has the collapse's colours at alpha 1, and both sides' mid-morph",
          "[color][morph]") {
  const MorphRuntime& rt = colouredDemo();
  const double fps = rt.timeline.fps;
  const MorphMarkers& mk = rt.setup.markers;
  MorphFrameSettings s;
  s.resolution = 48;
  auto atB = evaluateMorphImplicit(rt, mk.b / fps, 0.0, s);
  REQUIRE(atB.ok());
  REQUIRE(atB->mesh.colors.size() == atB->mesh.positions.size());
  const MorphFrame collapsed = evaluateMorphTransition(rt, mk.b / fps, false, 1.0, s);
  // Each collapsed vertex's colour against the closest implicit vertex's (a cell away at most).
  double sum = 0.0;
  std::vector<float> diffs;
  for (size_t v = 0; v < collapsed.mesh.positions.size(); v += 11) {
    const glm::vec3& p = collapsed.mesh.positions[v];
    size_t best = 0;
    float bd = INFINITY;
    for (size_t k = 0; k < atB->mesh.positions.size(); ++k) {
      const float d = glm::distance(p, atB->mesh.positions[k]);
      if (d < bd) bd = d, best = k;
    }
    const float d = glm::distance(glm::vec3(collapsed.mesh.colors[v]), glm::vec3(atB->mesh.colors[best]));
    diffs.push_back(d);
    sum += d;
  }
  std::sort(diffs.begin(), diffs.end());
  INFO("mean colour difference " << sum / double(diffs.size()) << ", 95th percentile " << diffs[diffs.size() * 95 / 100]);
  CHECK(sum / double(diffs.size()) < 0.03);
  CHECK(diffs[diffs.size() * 95 / 100] < 0.1f);
  // Mid-morph: the creature's red and blue and the gear's bronze are all on the surface.
  auto mid = evaluateMorphImplicit(rt, (mk.b + mk.c) / 2.0 / fps, 0.5, s);
  REQUIRE(mid.ok());
  REQUIRE(mid->mesh.colors.size() == mid->mesh.positions.size());
  const glm::vec3 bronze = rt.target.binding.vertexColors.front();
  size_t reds = 0, blues = 0, bronzes = 0;
  for (const glm::vec4& c : mid->mesh.colors) {
    reds += c.r > 0.5f && c.b < 0.3f && c.g < 0.2f;
    blues += c.b > 0.5f && c.r < 0.3f;
    bronzes += glm::distance(glm::vec3(c), bronze) < 0.1f;
  }
  INFO("red " << reds << ", blue " << blues << ", bronze " << bronzes << " of " << mid->mesh.colors.size());
  CHECK(reds > 0);
  CHECK(blues > 0);
  CHECK(bronzes > 0);
}
