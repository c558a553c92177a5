// Skeleton correspondence (standin_morph/skeleton_correspondence.h, standin_morph/correspondence_morph.h):
// chains split at branch joints and cover every segment; a rig matches itself chain for
// chain; the in-between stand-ins start on the source and end on the target; and the
// morph through B..C has no empty frame and a smaller largest frame-to-frame volume
// change than interpolation, on the demo pair and on the shared assets.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/project/project_io.h"
#include "core/standin_morph/chain_matching.h"
#include "core/standin_morph/correspondence_morph.h"
#include "core/standin_morph/morph_continuity.h"
#include "core/rig/pose.h"
#include "util/morph_fixtures.h"
#include "util/test_skip.h"

using namespace animorph;

namespace {

// Distance from x to the nearest segment of segs.
float toSegments(const std::vector<PosedSegment>& segs, const glm::vec3& x) {
  float best = 1e30f;
  for (const PosedSegment& s : segs) {
    const glm::vec3 d = s.b - s.a;
    const float l2 = glm::dot(d, d);
    const float f = l2 > 0.0f ? std::clamp(glm::dot(x - s.a, d) / l2, 0.0f, 1.0f) : 0.0f;
    best = std::min(best, glm::length(s.a + f * d - x));
  }
  return best;
}

struct BCMeasure {
  double largestChange = 0.0;
  int at = 0;
  size_t empty = 0;
};

// The morph's frames B..C polygonised with method (the project's other settings kept).
BCMeasure measureBC(Project p, const std::string& dir, MorphMethod method, int res) {
  p.morph.method = method;
  AssetCache assets;
  auto rt = prepareMorph(p, dir, assets);
  REQUIRE(rt.ok());
  if (method == MorphMethod::SkeletonCorrespondence) REQUIRE((*rt)->correspondence != nullptr);
  MorphFrameSettings fs;
  fs.resolution = res;
  const MorphMarkers& k = (*rt)->setup.markers;
  const ContinuitySummary s = measureContinuity(
      k.b, k.c,
      [&](int f) {
        auto fr = evaluateMorphFrame(**rt, p.timeline.frameToSec(f), fs);
        return fr ? std::move(fr->mesh) : TriangleMesh{};
      },
      false);
  return {s.maxVolumeChange, s.maxVolumeFrame, s.emptyFrames};
}

// Bound on the largest frame-to-frame volume change through B..C (measured at 32^3: 6.1 %
// on the demo and 7.9 % on tentacle -> plate; the interpolation's: 8.0 % and 9.8 %).
constexpr double kCorrespondenceVolumeBound = 0.12;

void compareWithInterpolation(const char* pair, const Project& p, const std::string& dir) {
  const BCMeasure interp = measureBC(p, dir, MorphMethod::Interpolation, 32);
  const BCMeasure corr = measureBC(p, dir, MorphMethod::SkeletonCorrespondence, 32);
  std::printf("%s B..C at 32^3: largest volume change interpolation %.1f%% (frame %d), skeleton correspondence %.1f%% (frame %d)\n",
              pair, 100.0 * interp.largestChange, interp.at, 100.0 * corr.largestChange, corr.at);
  INFO(pair << ": interpolation " << interp.largestChange << " at " << interp.at << ", correspondence "
            << corr.largestChange << " at " << corr.at);
  CHECK(corr.empty == 0);
  CHECK(corr.largestChange < kCorrespondenceVolumeBound);
  CHECK(corr.largestChange < interp.largestChange);
}

}  // namespace

TEST_CASE("skeleton chains: split at branch joints, every segment in one chain, intervals cover [0, 1]",
          "[morph][correspondence]") {
  const test::DemoMorph& d = test::demoMorph();
  const MorphRuntime& rt = *d.runtime;
  const SkeletonChains c = skeletonChains(*rt.source.character, rt.source.morph.standin);
  REQUIRE(c.mainRoot >= 0);
  CHECK(c.chains.size() > 1);  // the creature branches at its hips and chest
  std::vector<int> seen(rt.source.morph.standin.segments.size(), 0);
  for (size_t i = 0; i < c.chains.size(); ++i) {
    const SkeletonChain& ch = c.chains[i];
    REQUIRE(!ch.segments.empty());
    CHECK(ch.from.front() == 0.0f);
    CHECK(ch.to.back() == 1.0f);
    for (size_t k = 0; k < ch.segments.size(); ++k) {
      ++seen[size_t(ch.segments[k])];
      CHECK(ch.from[k] <= ch.to[k]);
      if (k > 0) CHECK(ch.from[k] == Approx(ch.to[k - 1]));
    }
    // Within a chain every joint but the last has one child chain-joint; the chain ends at a branch or tip.
    if (ch.parent >= 0) CHECK(ch.parent < int(i));
  }
  for (int n : seen) CHECK(n == 1);
  float lengths = 0.0f;
  for (const SkeletonChain& ch : c.chains) lengths += ch.length;
  CHECK(lengths == Approx(1.0f));
  CHECK(c.chains[size_t(c.mainRoot)].subtree == Approx(1.0f));
}

TEST_CASE("skeleton correspondence: a rig matches itself chain for chain, sides kept", "[morph][correspondence]") {
  const MorphRuntime& rt = *test::demoMorph().runtime;
  const Character& creature = *rt.source.character;
  const Standin& s = rt.source.morph.standin;
  const SkeletonCorrespondence c = correspondSkeletons(skeletonChains(creature, s), skeletonChains(creature, s));
  for (size_t i = 0; i < c.sourceMatch.size(); ++i) {
    INFO("chain " << i << " " << c.source.chains[i].name);
    CHECK(c.sourceMatch[i] == int(i));
    CHECK(c.cost[i] == Approx(0.0f).margin(1e-5));
  }
  // Left and right limbs differ by their side: a left chain costs more against a right one.
  int left = -1, right = -1;
  for (size_t i = 0; i < c.source.chains.size(); ++i) {
    if (c.source.chains[i].side < 0 && right < 0) right = int(i);
    if (c.source.chains[i].side > 0 && left < 0) left = int(i);
  }
  REQUIRE(left >= 0);
  REQUIRE(right >= 0);
  CHECK(chainMatchCost(c.source.chains[size_t(left)], c.source.chains[size_t(right)]) >= 0.5f);
}

TEST_CASE("correspondence morph: the source's stand-in at w = 0, the target's at w = 1, limbs on the target at 1",
          "[morph][correspondence]") {
  const MorphRuntime& rt = *test::demoMorph().runtime;
  auto c = morphSkeletonCorrespondence(rt.source, rt.target);
  REQUIRE(c.ok());
  const double t = 2.5;
  const MorphOperand src = posedOperand(rt.source, t, 0.5);
  const MorphOperand dst = posedOperand(rt.target, t, 0.5);
  const MorphOperand s0 = correspondenceOperand(*c, src, dst, 0.0f, true);
  const MorphOperand d1 = correspondenceOperand(*c, src, dst, 1.0f, false);
  REQUIRE(s0.segments.size() == src.segments.size());
  for (size_t i = 0; i < src.segments.size(); ++i) {
    CHECK(s0.segments[i].a == src.segments[i].a);
    CHECK(s0.segments[i].radius == src.segments[i].radius);
  }
  for (size_t i = 0; i < dst.segments.size(); ++i) CHECK(d1.segments[i].b == dst.segments[i].b);
  // At w = 1 every source segment has moved onto the target's posed stand-in (its chain's
  // partner, or the point its unmatched chain shrinks into); halfway it is in between.
  const MorphOperand s1 = correspondenceOperand(*c, src, dst, 1.0f, true);
  const MorphOperand sh = correspondenceOperand(*c, src, dst, 0.5f, true);
  for (size_t i = 0; i < s1.segments.size(); ++i) {
    CHECK(toSegments(dst.segments, s1.segments[i].a) < 1e-4f);
    CHECK(toSegments(dst.segments, s1.segments[i].b) < 1e-4f);
    CHECK(glm::length(sh.segments[i].a - 0.5f * (src.segments[i].a + s1.segments[i].a)) < 1e-4f);
  }
  // The program starts and ends on the stand-ins.
  for (float w : {0.0f, 1.0f}) {
    const FieldProgram corr =
        buildCorrespondenceMorphProgram(*c, src, dst, MorphMethod::Interpolation, w, {}, kDefaultInterpolationBound);
    const FieldProgram plain = buildMorphProgram(src, dst, MorphMethod::Interpolation, w, {}, kDefaultInterpolationBound);
    for (const PosedSegment& s : (w == 0.0f ? src : dst).segments) {
      const glm::vec3 x = 0.5f * (s.a + s.b) + glm::vec3(0.0f, s.radius, 0.0f);
      CHECK(test::fieldAt(corr, x) == Approx(test::fieldAt(plain, x)).margin(1e-6));
    }
  }
}

TEST_CASE("skeleton correspondence on the demo pair: no empty frame, smaller volume jumps than interpolation",
          "[morph][correspondence][continuity]") {
  const test::DemoMorph& d = test::demoMorph();
  compareWithInterpolation("creature -> gear", d.project, d.dir);
}

TEST_CASE("skeleton correspondence on tentacle.glb -> plate.glb: no empty frame, smaller volume jumps than interpolation",
          "[morph][correspondence][continuity]") {
  const Project* p = test::tentaclePlateMorph(ANIMORPH_SHARED_ASSETS);
  if (!p) {
    ANIMORPH_SKIP(ANIMORPH_SHARED_ASSETS << "/tentacle.glb or plate.glb not present: skipped");
  }
  compareWithInterpolation("tentacle -> plate", *p, ANIMORPH_SHARED_ASSETS);
}

TEST_CASE("skeleton correspondence: method and blend saved and read back, bad blend named", "[morph][correspondence]") {
  Project p = test::demoMorph().project;
  p.morph.method = MorphMethod::SkeletonCorrespondence;
  p.morph.correspondenceBlend = MorphMethod::SpaceTime;
  const std::string text = projectToJson(p);
  auto back = projectFromJson(text, "p.animorph");
  REQUIRE(back.ok());
  CHECK(back->morph.method == MorphMethod::SkeletonCorrespondence);
  CHECK(back->morph.correspondenceBlend == MorphMethod::SpaceTime);
  nlohmann::json j = nlohmann::json::parse(text);
  j["morph"]["correspondence_blend"] = "skeleton_correspondence";
  auto bad = projectFromJson(j.dump(), "p.animorph");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error() == "p.animorph: morph.correspondence_blend: expected \"interpolation\" or \"space_time\"");
}

TEST_CASE("skeleton correspondence needs a rig on both sides: a BlobTree side is refused by name",
          "[morph][correspondence]") {
  const MorphRuntime& rt = *test::demoMorph().runtime;
  MorphActorRuntime blob;
  blob.actor.id = "blob";
  blob.tree = std::make_shared<const BlobTree>();
  auto c = morphSkeletonCorrespondence(rt.source, blob);
  REQUIRE_FALSE(c.ok());
  CHECK(c.error() == "actor 'blob' is a BlobTree (no rig to correspond)");
}

TEST_CASE("chain matching as shown: partners named, unmatched chains shrink into their matched ancestor's partner",
          "[morph][correspondence]") {
  const MorphRuntime& rt = *test::demoMorph().runtime;
  REQUIRE(rt.correspondence != nullptr);  // the demo morphs by skeleton correspondence
  const SkeletonCorrespondence& c = *rt.correspondence;
  size_t unmatched = 0;
  for (size_t i = 0; i < c.source.chains.size(); ++i) {
    const std::string text = chainPartnerText(c.source, c.target, c.sourceMatch, int(i), "shrinks into");
    const int anchor = matchedAnchor(c.source, c.sourceMatch, int(i));
    INFO("chain " << i << " " << c.source.chains[i].name << ": " << text);
    if (c.sourceMatch[i] >= 0) {
      CHECK(anchor == int(i));
      CHECK(text == "<-> " + c.target.chains[size_t(c.sourceMatch[i])].name);
      continue;
    }
    ++unmatched;
    REQUIRE(anchor >= 0);
    CHECK(c.sourceMatch[size_t(anchor)] >= 0);
    CHECK(text == "shrinks into " + c.target.chains[size_t(c.sourceMatch[size_t(anchor)])].name);
  }
  CHECK(unmatched > 0);  // the creature has more chains than the gear
  CHECK(c.sourceMatch[size_t(c.source.mainRoot)] == c.target.mainRoot);
}
