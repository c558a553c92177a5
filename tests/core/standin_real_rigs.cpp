// Stand-ins fitted to rigs built like production exports (rigged_figure.h):
// helper-bone chains, node scales, a 60x scale, face and finger bones; the fit
// report in world units, its components check, and the rest-pose bounds.
#include <catch2/catch.hpp>

#include <algorithm>

#include "demo/creature.h"
#include "demo/rigged_figure.h"
#include "core/io/gltf_export.h"
#include "core/io/gltf_import.h"
#include "core/standin_morph/mesh_distance.h"
#include "core/project/new_morph_project.h"
#include "core/poly/polygonizer.h"
#include "core/rig/skinning.h"
#include "core/standin/character_pose.h"
#include "core/standin/fit_standin.h"
#include "util/temp_dir.h"

using namespace animorph;

namespace {

// The figure 60 units tall, through a .glb file (node scales as glTF stores them).
const Character& figure60() {
  static const Character c = [] {
    test::TempDir dir;
    RiggedFigureOptions o;
    o.height = 60.0f;
    const std::string path = dir.file("figure60.glb");
    REQUIRE(exportGlb(makeRiggedFigure(o), path).ok());
    auto imported = importGltf(path);
    REQUIRE(imported.ok());
    return *imported;
  }();
  return c;
}

Bounds boundsOf(const std::vector<glm::vec3>& pts) {
  Bounds b;
  for (const auto& p : pts) b.add(p);
  return b;
}

FitSettings previousFitter() {
  FitSettings fs;
  fs.bridgeHelpers = false;
  fs.mergeSmallBones = false;
  fs.repair.enabled = false;
  return fs;
}

}  // namespace

TEST_CASE("rest-pose bounds (info) apply node scales and equal the skinned vertices' bounds", "[standin][realrig]") {
  const Character& c = figure60();
  const Bounds b = poseBounds(c);
  const Bounds skinned = boundsOf(skinnedWorldPositions(c, nullptr, 0.0f));
  REQUIRE(!b.empty());
  const float tol = 1e-4f * skinned.diagonal();
  for (int a = 0; a < 3; ++a) {
    CHECK(b.min[a] == Approx(skinned.min[a]).margin(tol));
    CHECK(b.max[a] == Approx(skinned.max[a]).margin(tol));
  }
  // About 60 units tall in world space, while the mesh data sit in the
  // armature's centimetre space (what `info` printed before).
  CHECK(b.size().y == Approx(60.0f).epsilon(0.05));
  Bounds raw;
  for (const auto& m : c.meshes) raw.add(m.bounds());
  CHECK(raw.diagonal() > 10.0f * b.diagonal());
}

TEST_CASE("fit: helper bones, node scales and a 60x scale give one connected stand-in", "[standin][realrig]") {
  const Character& c = figure60();
  auto fit = fitStandin(c);
  REQUIRE(fit.ok());
  const FitReport& r = fit->report;
  INFO("mean " << r.meanDistance << " max " << r.maxDistance << " diag " << r.diagonal << " pieces "
               << r.standinComponents << " far " << r.farShare);
  for (const auto& p : r.problems) INFO(p);
  CHECK(r.meshComponents == 1);
  CHECK(r.standinComponents == 1);
  CHECK(r.largestGap == 0.0);
  CHECK(!r.poor);
  CHECK(r.helperBridges >= 4);  // spine and arm twist chains
  CHECK(r.bonesMerged >= 5);    // face bones inside the head
  CHECK(r.diagonal == Approx(poseBounds(c).diagonal()).epsilon(1e-4));

  // The error is in world units: compare with a direct measurement of each
  // vertex's distance to the polygonised stand-in surface.
  const CharacterPose pose = poseCharacter(c, nullptr, 0.0f, glm::mat4(1.0f));
  const auto segs = poseStandin(fit->standin, pose.globals, glm::mat4(1.0f));
  PolygonizeSettings ps;
  ps.resolution = 192;
  ps.bounds = posedStandinBounds(segs, 0.0f);
  auto poly = polygonize(standinProgram(fit->standin.kind, fit->standin.sharpness, segs), ps);
  REQUIRE(poly.ok());
  const PointMeshDistances direct = pointsToMeshDistance(pose.positions, poly->mesh);
  const double cell = poly->stats.cellSize;
  INFO("direct mean " << direct.meanDistance << " max " << direct.maxDistance << " cell " << cell);
  CHECK(r.meanDistance == Approx(direct.meanDistance).margin(0.1 * direct.meanDistance + 0.5 * cell));
  CHECK(r.maxDistance == Approx(direct.maxDistance).margin(0.15 * direct.maxDistance + cell));
  CHECK(r.meanError < 0.04);
}

TEST_CASE("fit: the previous fitter leaves the helper-bone rig in pieces and the report says so", "[standin][realrig]") {
  auto fit = fitStandin(figure60(), previousFitter());
  REQUIRE(fit.ok());
  const FitReport& r = fit->report;
  INFO("pieces " << r.standinComponents << " mean " << r.meanError);
  CHECK(r.standinComponents > 1);
  CHECK(r.largestGap > 0.0);
  CHECK(r.poor);
  REQUIRE(!r.poorBones.empty());
}

TEST_CASE("fit report: the components check fails on a deliberately broken stand-in", "[standin][realrig]") {
  const Character& c = figure60();
  auto fit = fitStandin(c);
  REQUIRE(fit.ok());
  Standin broken = fit->standin;
  // Move the segments of one forearm far out (in the joint's own units).
  const CharacterPose pose = poseCharacter(c, nullptr, 0.0f, glm::mat4(1.0f));
  int moved = 0;
  for (auto& seg : broken.segments) {
    if (c.nodes[size_t(seg.node)].name != "ForeArm_L") continue;
    const glm::mat4 inv = glm::inverse(pose.globals[size_t(seg.node)]);
    const glm::vec3 away = glm::vec3(inv * glm::vec4(0.0f, 0.0f, 0.4f * float(fit->report.diagonal), 0.0f));
    seg.a += away;
    seg.b += away;
    ++moved;
  }
  REQUIRE(moved > 0);
  const FitReport r = measureStandinFit(c, broken, FitSettings{});
  CHECK(r.standinComponents >= 2);
  CHECK(r.largestGap > 0.1 * r.diagonal);
  CHECK(r.poor);
  CHECK(std::find(r.poorBones.begin(), r.poorBones.end(), "ForeArm_L") != r.poorBones.end());
  REQUIRE(!r.problems.empty());
  CHECK(r.problems.front().find("ForeArm_L") != std::string::npos);
  // The good stand-in, measured the same way, is one piece.
  CHECK(measureStandinFit(c, fit->standin, FitSettings{}).standinComponents == 1);
}

TEST_CASE("new: a rescale over 10x that no unit explains needs consent, a poor fit is refused naming bones",
          "[standin][realrig]") {
  const Character creature = makeCreatureCharacter();
  const Character& figure = figure60();
  NewMorphSettings s;
  // 60 units tall against the 1 m creature: 42x its size, taken as inches (1 in = 0.0254 m).
  auto inches = makeMorphProject(creature, "creature.glb", figure, "figure60.glb", s);
  REQUIRE(inches.ok());
  CHECK(inches->warnings.empty());
  CHECK(inches->scaleApplied == Approx(0.0254));
  CHECK(std::any_of(inches->messages.begin(), inches->messages.end(),
                    [](const std::string& m) { return m.find("(probably authored in inches)") != std::string::npos; }));
  // 7 times that (about 290x): between centimetres and millimetres, no unit explains it.
  Character huge = figure;
  for (int r : huge.roots) huge.nodes[size_t(r)].rest.scale *= 7.0f, huge.nodes[size_t(r)].rest.translation *= 7.0f;
  auto refused = makeMorphProject(creature, "creature.glb", huge, "figure420.glb", s);
  REQUIRE(!refused.ok());
  CHECK(refused.error().find("figure420.glb") != std::string::npos);
  CHECK(refused.error().find("which no unit explains") != std::string::npos);
  s.allowLargeRescale = true;
  auto made = makeMorphProject(creature, "creature.glb", huge, "figure420.glb", s);
  REQUIRE(made.ok());
  CHECK(made->aligned);
  CHECK(made->scaleApplied < 0.01);  // the target shrinks by more than 100x
  REQUIRE(!made->warnings.empty());
  CHECK(made->warnings.front().find("scale") != std::string::npos);

  s.fit = previousFitter();
  auto poor = makeMorphProject(creature, "creature.glb", figure, "figure60.glb", s);
  REQUIRE(!poor.ok());
  CHECK(poor.error().find("poorly") != std::string::npos);
  s.acceptPoorFit = true;
  auto accepted = makeMorphProject(creature, "creature.glb", figure, "figure60.glb", s);
  REQUIRE(accepted.ok());
  CHECK(std::any_of(accepted->warnings.begin(), accepted->warnings.end(),
                    [](const std::string& w) { return w.find("POOR") != std::string::npos; }));
}
