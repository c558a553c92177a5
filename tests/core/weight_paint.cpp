// Weight-map painting: the brush (pixels, visibility, falloff, modes, mirror),
// strokes, the undoable command, and maps from glTF vertex colours.
#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>

#include "core/doc/document.h"
#include "core/doc/weight_map_command.h"
#include "core/io/gltf_export.h"
#include "core/io/gltf_import.h"
#include "core/paint/weight_brush.h"
#include "core/paint/weights_from_colors.h"
#include "core/rig/skinning.h"
#include "core/scene/scene_frame.h"
#include "util/mini_gltf.h"
#include "util/morph_fixtures.h"
#include "util/temp_dir.h"

using namespace animorph;

namespace {

// A square grid of (n+1)^2 vertices over [-half, half]^2 at depth z, facing
// +Z (towards the camera below) when front is true, -Z otherwise.
void addGrid(PaintMesh& m, int n, float half, float z, bool front = true) {
  const auto base = static_cast<uint32_t>(m.positions.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      glm::vec3 p(-half + 2.0f * half * i / n, -half + 2.0f * half * j / n, z);
      m.positions.push_back(p);
      m.normals.push_back(glm::vec3(0, 0, front ? 1.0f : -1.0f));
      m.restLocal.push_back(p);
    }
  auto at = [&](int i, int j) { return base + static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (front) m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
      else m.indices.insert(m.indices.end(), {a, c, b, a, d, c});
    }
}

// Looking from +Z at the origin, 5 m away, into an 800 x 600 viewport.
BrushView frontView() {
  BrushView v;
  v.camera.target = glm::vec3(0.0f);
  v.camera.yawRad = 0.0f;
  v.camera.pitchRad = 0.0f;
  v.camera.distanceM = 5.0f;
  v.viewportPx = {800.0f, 600.0f};
  return v;
}

uint32_t nearestVertex(const PaintMesh& m, glm::vec3 p) {
  uint32_t best = 0;
  for (uint32_t i = 1; i < m.positions.size(); ++i)
    if (glm::length(m.positions[i] - p) < glm::length(m.positions[best] - p)) best = i;
  return best;
}

glm::vec2 pixelOf(const BrushView& v, glm::vec3 p) { return glm::vec2(v.camera.worldToPixel(p, v.viewportPx)); }

bool hasHit(const std::vector<BrushHit>& hits, uint32_t vertex) {
  for (const auto& h : hits)
    if (h.vertex == vertex) return true;
  return false;
}

float variance(const std::vector<float>& w) {
  float mean = std::accumulate(w.begin(), w.end(), 0.0f) / static_cast<float>(w.size());
  float s = 0.0f;
  for (float x : w) s += (x - mean) * (x - mean);
  return s / static_cast<float>(w.size());
}

}  // namespace

TEST_CASE("brush falloff: 1 at the centre, 0 at the rim and outside", "[paint]") {
  for (BrushFalloff f : {BrushFalloff::Smooth, BrushFalloff::Linear, BrushFalloff::Constant}) {
    CHECK(brushFalloff(f, 0.0f) == Approx(1.0f));
    CHECK(brushFalloff(f, 1.5f) == 0.0f);
    CHECK(brushFalloff(f, 0.5f) <= 1.0f);
  }
  CHECK(brushFalloff(BrushFalloff::Linear, 0.25f) == Approx(0.75f));
  CHECK(brushFalloff(BrushFalloff::Smooth, 0.5f) == Approx(0.5f));
  CHECK(brushFalloff(BrushFalloff::Smooth, 1.0f) == Approx(0.0f));
  CHECK(brushFalloff(BrushFalloff::Constant, 0.99f) == 1.0f);
}

TEST_CASE("a dab raises the vertex under the cursor and not one outside the radius", "[paint]") {
  PaintMesh m;
  addGrid(m, 20, 1.0f, 0.0f);
  const BrushView view = frontView();
  const uint32_t centre = nearestVertex(m, {0.3f, 0.2f, 0.0f});
  const uint32_t far = nearestVertex(m, {-0.8f, -0.8f, 0.0f});
  const glm::vec2 cursor = pixelOf(view, m.positions[centre]);
  const float radiusPx = 30.0f;
  REQUIRE(glm::length(pixelOf(view, m.positions[far]) - cursor) > radiusPx);

  auto hits = verticesUnderBrush(m, view, cursor, radiusPx, BrushFalloff::Smooth);
  REQUIRE(hasHit(hits, centre));
  CHECK_FALSE(hasHit(hits, far));
  for (const auto& h : hits) CHECK(glm::length(pixelOf(view, m.positions[h.vertex]) - cursor) <= radiusPx + 1e-3f);

  std::vector<float> w(m.vertexCount(), 0.0f);
  BrushSettings s;
  s.radiusPx = radiusPx;
  s.strength = 0.4f;
  applyDab(w, hits, s, {}, {});
  CHECK(w[centre] == Approx(0.4f).margin(1e-3));
  CHECK(w[far] == 0.0f);
  // Farther from the centre means less paint (smooth falloff).
  for (const auto& h : hits) CHECK(w[h.vertex] <= w[centre] + 1e-6f);
}

TEST_CASE("subtract lowers weights, and every mode stays within [0, 1]", "[paint]") {
  PaintMesh m;
  addGrid(m, 10, 1.0f, 0.0f);
  const BrushView view = frontView();
  const uint32_t v = nearestVertex(m, {0.0f, 0.0f, 0.0f});
  auto hits = verticesUnderBrush(m, view, pixelOf(view, m.positions[v]), 40.0f, BrushFalloff::Constant);
  REQUIRE(hasHit(hits, v));
  BrushSettings s;
  s.strength = 0.7f;
  s.falloff = BrushFalloff::Constant;
  std::vector<float> w(m.vertexCount(), 0.5f);
  s.mode = BrushMode::Subtract;
  applyDab(w, hits, s, {}, {});
  CHECK(w[v] == 0.0f);  // 0.5 - 0.7, clamped
  s.mode = BrushMode::Add;
  applyDab(w, hits, s, {}, {});
  applyDab(w, hits, s, {}, {});
  CHECK(w[v] == 1.0f);  // 0 + 1.4, clamped
  for (float x : w) CHECK((x >= 0.0f && x <= 1.0f));
  s.mode = BrushMode::Fill;
  s.strength = 0.25f;
  applyDab(w, {}, s, {}, {});
  for (float x : w) CHECK(x == 0.25f);
}

TEST_CASE("smooth pulls weights towards their neighbours' mean and lowers the variance", "[paint]") {
  PaintMesh m;
  addGrid(m, 12, 1.0f, 0.0f);
  const BrushView view = frontView();
  std::vector<float> w(m.vertexCount());
  for (size_t i = 0; i < w.size(); ++i) w[i] = (i % 2) ? 1.0f : 0.0f;  // a checkerboard-like pattern
  auto hits = verticesUnderBrush(m, view, pixelOf(view, {0, 0, 0}), 400.0f, BrushFalloff::Constant);
  REQUIRE(hits.size() == m.vertexCount());
  BrushSettings s;
  s.mode = BrushMode::Smooth;
  s.strength = 0.5f;
  const float before = variance(w);
  applyDab(w, hits, s, vertexNeighbours(m.vertexCount(), m.indices), {});
  CHECK(variance(w) < 0.5f * before);
  for (float x : w) CHECK((x >= 0.0f && x <= 1.0f));
}

TEST_CASE("X mirror paints the vertex mirrored across the actor's X = 0 plane", "[paint]") {
  PaintMesh m;
  addGrid(m, 20, 1.0f, 0.0f);
  const BrushView view = frontView();
  const uint32_t right = nearestVertex(m, {0.6f, 0.3f, 0.0f});
  const uint32_t left = nearestVertex(m, {-0.6f, 0.3f, 0.0f});
  auto mirror = mirrorVertexMap(m.restLocal, 0.01f);
  REQUIRE(mirror[right] == static_cast<int32_t>(left));
  REQUIRE(mirror[left] == static_cast<int32_t>(right));

  BrushSettings s;
  s.radiusPx = 20.0f;
  s.strength = 0.5f;
  WeightStroke plain(m, {}, s, view);
  plain.moveTo(pixelOf(view, m.positions[right]));
  CHECK(plain.weights()[right] > 0.4f);
  CHECK(plain.weights()[left] == 0.0f);  // far outside the brush

  s.mirrorX = true;
  WeightStroke mirrored(m, {}, s, view);
  mirrored.moveTo(pixelOf(view, m.positions[right]));
  CHECK(mirrored.weights()[left] == Approx(mirrored.weights()[right]));
  CHECK(mirrored.verticesTouched() == 2 * plain.verticesTouched());
}

TEST_CASE("vertices hidden behind the mesh or facing away are not painted", "[paint]") {
  PaintMesh m;
  addGrid(m, 10, 0.5f, 0.0f);          // front sheet, 0..120 vertices
  const size_t frontCount = m.vertexCount();
  addGrid(m, 10, 0.5f, -0.5f);         // a second sheet behind it, also facing the camera
  const size_t hiddenEnd = m.vertexCount();
  addGrid(m, 10, 0.5f, 0.3f, false);   // a sheet in front, facing away (its back to the camera)
  const BrushView view = frontView();
  // A second view that sees only the two facing sheets from the side: nothing occludes there.
  auto hits = verticesUnderBrush(m, view, pixelOf(view, {0, 0, 0}), 60.0f, BrushFalloff::Constant);
  size_t front = 0, hidden = 0, away = 0;
  for (const auto& h : hits) {
    if (h.vertex < frontCount) ++front;
    else if (h.vertex < hiddenEnd) ++hidden;
    else ++away;
  }
  CHECK(front > 5);
  CHECK(hidden == 0);
  CHECK(away == 0);

  // Without the front sheet the back sheet is painted: the depth test, not the distance, hid it.
  PaintMesh back;
  addGrid(back, 10, 0.5f, -0.5f);
  CHECK(verticesUnderBrush(back, view, pixelOf(view, {0, 0, -0.5f}), 60.0f, BrushFalloff::Constant).size() > 5);
}

TEST_CASE("a stroke dabs along the cursor's path at the brush spacing", "[paint]") {
  PaintMesh m;
  addGrid(m, 40, 1.0f, 0.0f);
  const BrushView view = frontView();
  BrushSettings s;
  s.radiusPx = 20.0f;
  s.spacing = 0.5f;  // a dab every 10 px
  s.strength = 0.2f;
  WeightStroke stroke(m, std::vector<float>(3, 0.9f) /* wrong size: replaced by zeros */, s, view);
  glm::vec2 a = pixelOf(view, {-0.6f, 0.0f, 0.0f}), b = pixelOf(view, {0.6f, 0.0f, 0.0f});
  CHECK(stroke.moveTo(a) == 1);
  int dabs = stroke.moveTo(b);
  CHECK(dabs == static_cast<int>(std::floor(glm::length(b - a) / 10.0f)));
  const auto& w = stroke.weights();
  REQUIRE(w.size() == m.vertexCount());
  CHECK(w[nearestVertex(m, {0.0f, 0.0f, 0.0f})] > 0.2f);   // several dabs overlap there
  CHECK(w[nearestVertex(m, {0.0f, 0.8f, 0.0f})] == 0.0f);  // off the path
}

TEST_CASE("the paint mesh of the demo creature is its posed mesh in weight-map order", "[paint]") {
  const auto& dm = test::demoMorph();
  AssetCache assets;
  const Actor* creature = dm.project.findActor(dm.project.morph.sourceActorId);
  REQUIRE(creature);
  SceneFrame frame = evaluateScene(dm.project, dm.dir, assets, 0.5);
  PaintMesh pm = paintMeshFromFrame(frame, creature->id);
  const Character& c = test::demoCreature();
  REQUIRE(pm.vertexCount() == c.totalVertices());
  REQUIRE(pm.restLocal.size() == pm.vertexCount());
  CHECK(pm.indices.size() == 3 * c.totalTriangles());
  // Posed like rig/skinning at the actor's clip time, under the actor's transform.
  const AnimationClip& clip = c.clips[static_cast<size_t>(creature->clip)];
  auto expected = skinnedWorldPositions(c, &clip, static_cast<float>(actorClipTimeSec(*creature, clip, 0.5)));
  const glm::mat4 actorM = creature->transform.matrix();
  for (size_t i = 0; i < pm.vertexCount(); i += 97)
    CHECK(glm::length(pm.positions[i] - glm::vec3(actorM * glm::vec4(expected[i], 1.0f))) < 1e-4f);
  // The creature is symmetric about its X = 0 plane: most vertices find their mirror.
  auto mirror = mirrorVertexMap(pm.restLocal, 0.01f * c.meshes[0].bounds().diagonal());
  size_t found = 0;
  for (int32_t k : mirror) found += k >= 0;
  CHECK(found > pm.vertexCount() * 9 / 10);
}

TEST_CASE("a weight-map command is one undo step that restores the map exactly", "[paint]") {
  const auto& dm = test::demoMorph();
  Document doc;
  doc.reset(dm.project, dm.projectPath);
  const std::string id = dm.project.morph.sourceActorId;
  REQUIRE(doc.project().morph.findActor(id)->weightMap.empty());
  std::vector<float> painted(test::demoCreature().totalVertices(), 0.0f);
  painted[3] = 0.75f;
  auto cmd = setWeightMapCommand(doc.project(), id, painted, "Paint weights");
  REQUIRE(cmd.ok());
  doc.execute(std::move(*cmd));
  CHECK(doc.project().morph.findActor(id)->weightMap == painted);
  REQUIRE(doc.undo());
  CHECK(doc.project().morph.findActor(id)->weightMap.empty());
  REQUIRE(doc.redo());
  CHECK(doc.project().morph.findActor(id)->weightMap[3] == 0.75f);

  auto notMorph = setWeightMapCommand(doc.project(), "nobody", painted, "Paint weights");
  REQUIRE_FALSE(notMorph.ok());
  CHECK(notMorph.error().find("'nobody'") != std::string::npos);
  painted[5] = 1.5f;
  auto bad = setWeightMapCommand(doc.project(), id, painted, "Paint weights");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("value 5") != std::string::npos);
}

TEST_CASE("COLOR_0 is imported and becomes a weight map (red, luminance or alpha)", "[paint][gltf]") {
  test::TempDir tmp;
  test::MiniGltf g;
  int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3");
  int idx = g.addU16({0, 1, 2, 1, 3, 2}, "SCALAR");
  int col = g.addU8({255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0, 51, 51, 51, 255}, "VEC4");
  g.json()["accessors"][col]["normalized"] = true;
  g.addMesh(pos, idx, {{"COLOR_0", col}});
  g.json()["nodes"].push_back({{"mesh", 0}});
  auto c = importGltf(g.write(tmp.path().string(), "painted.gltf"));
  REQUIRE(c.ok());
  REQUIRE(c->meshes[0].colors.size() == 4);
  CHECK(c->meshes[0].colors[1].g == Approx(1.0f));
  CHECK(c->meshes[0].colors[1].a == Approx(128.0f / 255.0f));

  auto red = weightMapFromVertexColors(*c, ColorChannel::Red);
  REQUIRE(red.ok());
  REQUIRE(red->size() == 4);
  CHECK((*red)[0] == 1.0f);
  CHECK((*red)[1] == 0.0f);
  CHECK((*red)[2] == 0.0f);
  CHECK((*red)[3] == Approx(0.2f).margin(1e-6));
  auto alpha = weightMapFromVertexColors(*c, ColorChannel::Alpha);
  REQUIRE(alpha.ok());
  CHECK((*alpha)[2] == 0.0f);
  CHECK((*alpha)[1] == Approx(128.0f / 255.0f));
  auto lum = weightMapFromVertexColors(*c, ColorChannel::Luminance);
  REQUIRE(lum.ok());
  CHECK((*lum)[1] == Approx(0.7152f));
  CHECK((*lum)[3] == Approx(0.2f).margin(1e-5));

  // Our own export writes COLOR_0 back (a round trip through a .glb).
  auto glb = exportGlb(*c, tmp.file("painted.glb"));
  REQUIRE(glb.ok());
  auto again = importGltf(tmp.file("painted.glb"));
  REQUIRE(again.ok());
  REQUIRE(again->meshes[0].colors.size() == 4);
  for (int i = 0; i < 4; ++i) CHECK(glm::length(again->meshes[0].colors[i] - c->meshes[0].colors[i]) < 1e-6f);
}

TEST_CASE("a character without vertex colours gives a clear error naming its file", "[paint][gltf]") {
  Character c = test::demoCreature();
  c.sourcePath = "/somewhere/creature.glb";
  auto r = weightMapFromVertexColors(c, ColorChannel::Red);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().rfind("creature.glb: no vertex colours (COLOR_0)", 0) == 0);
  CHECK(parseColorChannel("alpha") == ColorChannel::Alpha);
  CHECK(parseColorChannel("color") == ColorChannel::Red);
  CHECK_FALSE(parseColorChannel("green").has_value());
}
