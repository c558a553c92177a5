// Hand re-pairing of skeleton chains (standin_morph/chain_pair.h, doc/chain_pair_commands.h):
// artist pairs are kept and the automatic assignment fills in the rest; an artist
// pair involving a main root chain wins over the root rule; names that are not in
// the rig are skipped with a warning naming the element; the pairs are saved
// (older files without them load unchanged) and every edit undoes exactly.
#include <catch2/catch.hpp>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "core/doc/chain_pair_commands.h"
#include "core/doc/document.h"
#include "core/doc/morph_create.h"
#include "core/project/project_io.h"
#include "core/standin_morph/chain_matching.h"
#include "core/standin_morph/correspondence_morph.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

// The demo's creature against itself (8 chains a side; the automatic matching pairs each
// chain with itself), and creature -> gear (the gear has one chain, its hub).
const SkeletonChains& creatureChains() {
  static const SkeletonChains c = [] {
    const MorphRuntime& rt = *test::demoMorph().runtime;
    return skeletonChains(*rt.source.character, rt.source.morph.standin);
  }();
  return c;
}
const SkeletonChains& gearChains() {
  static const SkeletonChains c = [] {
    const MorphRuntime& rt = *test::demoMorph().runtime;
    return skeletonChains(*rt.target.character, rt.target.morph.standin);
  }();
  return c;
}
SkeletonCorrespondence selfPairs(const std::vector<ChainPair>& pairs = {}) {
  return correspondSkeletons(creatureChains(), creatureChains(), pairs);
}
SkeletonCorrespondence demoPairs(const std::vector<ChainPair>& pairs = {}) {
  return correspondSkeletons(creatureChains(), gearChains(), pairs);
}

// targetMatch is sourceMatch's inverse.
void checkConsistent(const SkeletonCorrespondence& c) {
  for (size_t r = 0; r < c.sourceMatch.size(); ++r)
    if (c.sourceMatch[r] >= 0) CHECK(c.targetMatch[size_t(c.sourceMatch[r])] == int(r));
  for (size_t k = 0; k < c.targetMatch.size(); ++k)
    if (c.targetMatch[k] >= 0) CHECK(c.sourceMatch[size_t(c.targetMatch[k])] == int(k));
}

}  // namespace

TEST_CASE("chain pairs: an artist pair is kept, the automatic matching fills in the rest around it",
          "[morph][correspondence][chain_pairs]") {
  const SkeletonCorrespondence a = selfPairs();
  REQUIRE(a.target.chains.size() >= 3);
  // A matched non-root source chain, re-paired with another non-root target chain.
  int r = -1;
  for (size_t i = 0; i < a.sourceMatch.size() && r < 0; ++i)
    if (int(i) != a.source.mainRoot && a.sourceMatch[i] >= 0) r = int(i);
  REQUIRE(r >= 0);
  int k = -1;
  for (size_t j = 0; j < a.target.chains.size() && k < 0; ++j)
    if (int(j) != a.target.mainRoot && int(j) != a.sourceMatch[size_t(r)]) k = int(j);
  REQUIRE(k >= 0);
  const SkeletonCorrespondence c = selfPairs({{a.source.chains[size_t(r)].name, a.target.chains[size_t(k)].name}});
  CHECK(c.warnings.empty());
  CHECK(c.sourceMatch[size_t(r)] == k);
  CHECK(c.pinned[size_t(r)]);
  CHECK(c.automatic[size_t(r)] == a.sourceMatch[size_t(r)]);  // what auto gives it without the pair
  CHECK(c.sourceMatch[size_t(a.source.mainRoot)] == a.target.mainRoot);  // no root in the pair: the rule holds
  for (size_t i = 0; i < c.sourceMatch.size(); ++i) {
    if (int(i) == r) continue;
    CHECK_FALSE(c.pinned[i]);
    CHECK(c.sourceMatch[i] != k);  // nobody else takes the artist's target
    CHECK(c.automatic[i] == c.sourceMatch[i]);
  }
  // The rest is matched by the automatic rule among the chains left: each within the cost bound.
  for (size_t i = 0; i < c.sourceMatch.size(); ++i)
    if (int(i) != r && c.sourceMatch[i] >= 0) CHECK(c.cost[i] <= kMaxChainMatchCost);
  checkConsistent(c);

  // Left unmatched by hand: it stays unmatched even though the automatic matching pairs it.
  const SkeletonCorrespondence u = selfPairs({{a.source.chains[size_t(r)].name, std::nullopt}});
  CHECK(u.sourceMatch[size_t(r)] == -1);
  CHECK(u.pinned[size_t(r)]);
  CHECK(u.automatic[size_t(r)] == a.sourceMatch[size_t(r)]);
  checkConsistent(u);
}

TEST_CASE("chain pairs: an artist pair involving a main root chain wins over the root rule",
          "[morph][correspondence][chain_pairs]") {
  // Creature -> gear: the rule pairs the hips with the hub; the chest (the larger chain) stays unmatched.
  const SkeletonCorrespondence a = demoPairs();
  const int sr = a.source.mainRoot, tr = a.target.mainRoot;
  const int chest = chainNamed(a.source, "chest");
  REQUIRE(chest >= 0);
  REQUIRE(a.sourceMatch[size_t(sr)] == tr);
  REQUIRE(a.sourceMatch[size_t(chest)] == -1);
  // The artist pairs the chest with the hub: the hips stay unmatched (they shrink into the root).
  const SkeletonCorrespondence c = demoPairs({{"chest", std::string("hub")}});
  CHECK(c.sourceMatch[size_t(chest)] == tr);
  CHECK(c.sourceMatch[size_t(sr)] == -1);
  CHECK(c.automatic[size_t(chest)] == -1);
  CHECK(matchedAnchor(c.source, c.sourceMatch, chainNamed(a.source, "neck")) == chest);  // the neck goes with the chest
  CHECK(chainPartnerText(c.source, c.target, c.sourceMatch, sr, "shrinks into") == "shrinks into the root");
  checkConsistent(c);
  // The source's root left unmatched: the hub is matched by cost alone, not forced onto the hips.
  const SkeletonCorrespondence u = demoPairs({{a.source.chains[size_t(sr)].name, std::nullopt}});
  CHECK(u.sourceMatch[size_t(sr)] == -1);
  CHECK(u.automatic[size_t(sr)] == tr);
  if (u.targetMatch[size_t(tr)] >= 0)
    CHECK(chainMatchCost(a.source.chains[size_t(u.targetMatch[size_t(tr)])], a.target.chains[size_t(tr)]) <=
          kMaxChainMatchCost);
  checkConsistent(u);
  // Creature -> creature: the root paired with a limb takes it, the other root is matched by cost.
  const SkeletonCorrespondence self = selfPairs();
  const int limb = chainNamed(self.target, "tail1");
  REQUIRE(limb >= 0);
  const SkeletonCorrespondence s = selfPairs({{self.source.chains[size_t(sr)].name, std::string("tail1")}});
  CHECK(s.sourceMatch[size_t(sr)] == limb);
  if (const int m = s.targetMatch[size_t(self.target.mainRoot)]; m >= 0)  // by cost, not forced
    CHECK(chainMatchCost(self.source.chains[size_t(m)], self.target.chains[size_t(self.target.mainRoot)]) <=
          kMaxChainMatchCost);
  checkConsistent(s);
}

TEST_CASE("chain pairs: names not in the rigs, a source twice or a target taken twice are skipped with a warning",
          "[morph][correspondence][chain_pairs]") {
  const SkeletonCorrespondence a = selfPairs();
  const std::string s0 = a.source.chains[0].name, s1 = a.source.chains[1].name;
  const std::string t0 = a.target.chains[0].name;
  const SkeletonCorrespondence c = selfPairs({{"NoSuchJoint", t0},
                                             {s0, std::string("NoSuchTarget")},
                                             {s1, t0},
                                             {s1, std::nullopt},
                                             {s0, t0}});
  REQUIRE(c.warnings.size() == 4);
  CHECK(c.warnings[0] == "chain_pairs[0].source: no source chain starts at joint 'NoSuchJoint': pair ignored");
  CHECK(c.warnings[1] == "chain_pairs[1].target: no target chain starts at joint 'NoSuchTarget': pair ignored");
  CHECK(c.warnings[2] == "chain_pairs[3].source: chain '" + s1 + "' is paired by an earlier entry: pair ignored");
  CHECK(c.warnings[3] == "chain_pairs[4].target: chain '" + t0 + "' is already paired with '" + s1 + "': pair ignored");
  CHECK(c.sourceMatch[1] == 0);
  CHECK(c.pinned[1]);
  CHECK_FALSE(c.pinned[0]);

  // Through a project: the morph prepares, the note names the element, the chain stays automatic.
  Project p = test::demoMorph().project;
  p.morph.chainPairs = {{"NoSuchJoint", std::string("hub")}};
  AssetCache assets;
  auto rt = prepareMorph(p, test::demoMorph().dir, assets);
  REQUIRE(rt);
  REQUIRE((*rt)->correspondence);
  CHECK((*rt)->correspondence->sourceMatch == demoPairs().sourceMatch);
  bool noted = false;
  for (const std::string& n : (*rt)->notes)
    noted |= n == "skeleton correspondence: morph.chain_pairs[0].source: no source chain starts at joint "
                  "'NoSuchJoint': pair ignored";
  CHECK(noted);
}

TEST_CASE("chain pairs: the prepared morph follows them, the re-paired chain lands on its new partner",
          "[morph][correspondence][chain_pairs]") {
  Project p = test::demoMorph().project;
  REQUIRE(p.morph.method == MorphMethod::SkeletonCorrespondence);
  // The chest's segments at w = 1: their summed length, and their largest distance to the hub's segments.
  auto chestOnHub = [&](const std::vector<ChainPair>& pairs, float& farthest) {
    p.morph.chainPairs = pairs;
    AssetCache assets;
    auto rt = prepareMorph(p, test::demoMorph().dir, assets);
    REQUIRE(rt);
    REQUIRE((*rt)->correspondence);
    const SkeletonCorrespondence& c = *(*rt)->correspondence;
    const int chest = chainNamed(c.source, "chest");
    REQUIRE(chest >= 0);
    const double t = p.timeline.frameToSec((*rt)->setup.markers.c);
    const MorphOperand src = posedOperand((*rt)->source, t, 1.0), dst = posedOperand((*rt)->target, t, 1.0);
    const MorphOperand moved = correspondenceOperand(c, src, dst, 1.0f, true);
    float length = 0.0f;
    farthest = 0.0f;
    for (int seg : c.source.chains[size_t(chest)].segments) {
      const PosedSegment& m = moved.segments[size_t(seg)];
      length += glm::length(m.b - m.a);
      for (const glm::vec3& x : {m.a, m.b}) {
        float best = 1e30f;
        for (int ts : c.target.chains[size_t(c.target.mainRoot)].segments) {
          const PosedSegment& s = dst.segments[size_t(ts)];
          const glm::vec3 d = s.b - s.a;
          const float f = glm::dot(d, d) > 0.0f ? std::clamp(glm::dot(x - s.a, d) / glm::dot(d, d), 0.0f, 1.0f) : 0.0f;
          best = std::min(best, glm::length(s.a + f * d - x));
        }
        farthest = std::max(farthest, best);
      }
    }
    return length;
  };
  float farAuto = 0.0f, farPaired = 0.0f;
  const float automatic = chestOnHub({}, farAuto);
  const float paired = chestOnHub({{"chest", std::string("hub")}}, farPaired);
  CHECK(automatic == Approx(0.0f).margin(1e-5));  // unmatched: it shrinks into a point
  INFO("the chest's summed length on the hub " << paired);
  CHECK(paired > 1e-2f);  // paired: spread along the hub
  CHECK(farPaired < 1e-3f);
}

TEST_CASE("chain pairs: saved and read back, absent in older files, bad entries named", "[morph][chain_pairs][file]") {
  Project p = test::demoMorph().project;
  p.morph.chainPairs.clear();
  const std::string plain = projectToJson(p);
  CHECK(nlohmann::json::parse(plain)["morph"].count("chain_pairs") == 0);  // older files stay byte-identical
  auto old = projectFromJson(plain, "p.animorph");
  REQUIRE(old.ok());
  CHECK(old->morph.chainPairs.empty());

  p.morph.chainPairs = {{"chest", std::string("hub")}, {"tail1", std::nullopt}};
  const std::string text = projectToJson(p);
  const nlohmann::json saved = nlohmann::json::parse(text)["morph"]["chain_pairs"];
  CHECK(saved == nlohmann::json::parse(R"([{"source": "chest", "target": "hub"}, {"source": "tail1", "target": null}])"));
  auto back = projectFromJson(text, "p.animorph");
  REQUIRE(back.ok());
  CHECK(back->morph.chainPairs == p.morph.chainPairs);
  CHECK(back->morph == p.morph);

  auto fails = [&](const char* pairs) {
    nlohmann::json j = nlohmann::json::parse(text);
    j["morph"]["chain_pairs"] = nlohmann::json::parse(pairs);
    auto r = projectFromJson(j.dump(), "p.animorph");
    REQUIRE_FALSE(r.ok());
    return r.error();
  };
  CHECK(fails(R"({"source": "chest"})") ==
        "p.animorph: morph.chain_pairs: expected an array of {\"source\": JOINT, \"target\": JOINT or null}");
  CHECK(fails(R"([{"source": "chest"}])") ==
        "p.animorph: morph.chain_pairs[0].target: missing (a joint name, or null: left unmatched)");
  CHECK(fails(R"([{"source": "", "target": null}])") == "p.animorph: morph.chain_pairs[0].source: expected a joint name");
  CHECK(fails(R"([{"source": "chest", "target": 3}])") ==
        "p.animorph: morph.chain_pairs[0].target: expected a joint name, or null: left unmatched");
  CHECK(fails(R"([{"source": "chest", "target": null}, {"source": "chest", "target": "hub"}])") ==
        "p.animorph: morph.chain_pairs[1].source: chain 'chest' is already paired by an earlier entry");
}

TEST_CASE("chain pair commands: one undo step each, a taken target moves, reset one and all",
          "[morph][chain_pairs][undo]") {
  Document doc;
  doc.reset(test::demoMorph().project, "");
  REQUIRE(doc.project().morph.chainPairs.empty());
  doc.execute(setChainPairCommand(doc.project(), {"chest", std::string("hub")}));
  CHECK(doc.history().size() == 1);
  CHECK(doc.project().morph.chainPairs == std::vector<ChainPair>{{"chest", std::string("hub")}});
  CHECK(setChainPairCommand(doc.project(), {"chest", std::string("hub")}) == nullptr);  // nothing to change
  doc.execute(setChainPairCommand(doc.project(), {"tail1", std::nullopt}));
  // The neck takes the hub: the chest's pair gives it up (it would otherwise be ignored).
  doc.execute(setChainPairCommand(doc.project(), {"neck", std::string("hub")}));
  CHECK(doc.project().morph.chainPairs ==
        std::vector<ChainPair>{{"tail1", std::nullopt}, {"neck", std::string("hub")}});
  REQUIRE(doc.undo());
  CHECK(doc.project().morph.chainPairs ==
        std::vector<ChainPair>{{"chest", std::string("hub")}, {"tail1", std::nullopt}});
  REQUIRE(doc.redo());
  CHECK(resetChainPairCommand(doc.project(), "chest") == nullptr);  // no pair of its own any more
  doc.execute(resetChainPairCommand(doc.project(), "tail1"));
  CHECK(doc.project().morph.chainPairs == std::vector<ChainPair>{{"neck", std::string("hub")}});
  doc.execute(resetAllChainPairsCommand(doc.project()));
  CHECK(doc.project().morph.chainPairs.empty());
  CHECK(resetAllChainPairsCommand(doc.project()) == nullptr);
  CHECK(doc.history().size() == 5);
  for (int i = 0; i < 5; ++i) REQUIRE(doc.undo());
  CHECK(doc.project().morph == test::demoMorph().project.morph);
  CHECK_FALSE(doc.dirty());
}

TEST_CASE("chain pairs follow the sides: reversed by a swap, kept by the same choice, dropped for other actors",
          "[morph][chain_pairs]") {
  Document doc;
  Project p = test::demoMorph().project;
  p.morph.chainPairs = {{"chest", std::string("hub")}, {"neck", std::nullopt}};
  doc.reset(p, "");
  doc.execute(swapMorphSidesCommand(doc.project()));
  CHECK(doc.project().morph.sourceActorId == p.morph.targetActorId);
  CHECK(doc.project().morph.chainPairs == std::vector<ChainPair>{{"hub", std::string("chest")}});
  REQUIRE(doc.undo());
  CHECK(doc.project().morph.chainPairs == p.morph.chainPairs);

  AssetCache assets;
  const std::string& dir = test::demoMorph().dir;
  const MorphSetup& m = p.morph;
  auto same = proposeMorph(p, dir, assets, {m.sourceActorId, m.targetActorId, m.method, m.markers});
  REQUIRE(same);
  CHECK(same->chainPairs == m.chainPairs);
  auto swapped = proposeMorph(p, dir, assets, {m.targetActorId, m.sourceActorId, m.method, m.markers});
  REQUIRE(swapped);
  CHECK(swapped->chainPairs == std::vector<ChainPair>{{"hub", std::string("chest")}});
  // Another actor on one side: the pairs named the old rig's joints.
  Project three = p;
  Actor other = *three.findActor(m.targetActorId);
  other.id = "gear2";
  three.actors.push_back(other);
  auto changed = proposeMorph(three, dir, assets, {m.sourceActorId, "gear2", m.method, m.markers});
  REQUIRE(changed);
  CHECK(changed->chainPairs.empty());
}
