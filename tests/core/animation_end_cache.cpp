#include <catch2/catch.hpp>

#include <random>

#include "core/doc/blobtree_commands.h"
#include "core/doc/document.h"
#include "core/project/animation_end_cache.h"
#include "core/scene/scene_frame.h"
#include "demo/blob_creature.h"

using namespace animorph;

namespace {

// A document with one looping BlobTree actor "blob" (the starter tree) whose sphere's radius is
// keyed at 0, 1 and 2 s through the edit commands: its tree ends at 2 s.
std::unique_ptr<Document> keyedDocument(ParamAddress& radius) {
  auto d = std::make_unique<Document>();
  Project p;
  p.actors.push_back(makeBlobTreeActor(p, "blob"));
  d->reset(p, "");
  const BlobTree& tree = d->project().findActor("blob")->blobTree;
  const int sphere = tree.root.children.at(0).id;
  radius = {sphere, paramIndex(tree.find(sphere)->type, "radius"), -1};
  for (auto [t, v] : {std::pair{0.0, 0.4f}, {1.0, 0.8f}, {2.0, 0.5f}}) {
    auto c = setBlobParamCommand(d->project(), "blob", radius, t, v, true);
    REQUIRE(c.ok());
    d->execute(std::move(*c));
  }
  return d;
}

const Actor& blobOf(const Document& d) { return *d.project().findActor("blob"); }

// The kept end of the actor's tree at the document's revision, and the looped tree time at
// scene time 2.6 s through the scene evaluation's path (blobActorTimeSec inside a scope).
double keptEnd(const Document& d) { return cachedAnimationEndSec(blobOf(d).blobTree, &d, d.revision()); }
double loopedAt2p6(const Document& d) {
  AnimationEndScope ends(d.project(), &d, d.revision());
  return blobActorTimeSec(blobOf(d), 2.6);
}

}  // namespace

TEST_CASE("the kept tree end follows a key moved past the end then its undo and redo and a load", "[blobtree][scene]") {
  ParamAddress radius;
  auto d = keyedDocument(radius);
  REQUIRE(keptEnd(*d) == 2.0);
  CHECK(loopedAt2p6(*d) == Approx(0.6));
  // The middle key dragged 1.5 s later through the curve editor's command: the tree now ends at 2.5 s.
  const BlobTree original = blobOf(*d).blobTree;
  auto move = moveBlobKeysCommand(d->project(), "blob", original, {{{radius, 1}, 0}}, 1.5, 0.0f);
  REQUIRE(move.ok());
  d->execute(std::move(*move));
  CHECK(keptEnd(*d) == 2.5);
  CHECK(loopedAt2p6(*d) == Approx(0.1));
  REQUIRE(d->undo());
  CHECK(keptEnd(*d) == 2.0);
  CHECK(loopedAt2p6(*d) == Approx(0.6));
  REQUIRE(d->redo());
  CHECK(keptEnd(*d) == 2.5);
  // Deleting the moved key (now the last, at 2.5 s) ends the tree at 2 s again.
  auto del = deleteBlobKeysCommand(d->project(), "blob", {{radius, 2}});
  REQUIRE(del.ok());
  d->execute(std::move(*del));
  CHECK(keptEnd(*d) == 2.0);
  // A load (File > New / Open replace the project) of the same project whose last key sits at 4 s.
  Project p = d->project();
  REQUIRE(moveKeys(p.actors[0].blobTree, {{{radius, 1}, 0}}, 2.0, 0.0f).ok());
  d->reset(p, "");
  CHECK(keptEnd(*d) == 4.0);
  // Every answer equals a fresh walk.
  CHECK(keptEnd(*d) == animationEndSec(blobOf(*d).blobTree));
}

TEST_CASE("scene evaluation at many times walks each looping tree once per document revision", "[blobtree][scene]") {
  ParamAddress radius;
  auto d = keyedDocument(radius);
  Actor creature = makeBlobTreeActor(d->project(), "creature");
  creature.blobTree = makeBlobCreature();
  {
    Project p = d->project();
    p.actors.push_back(creature);
    d->reset(p, "");
  }
  AssetCache assets;
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> time(-3.0, 9.0);
  auto evaluateMany = [&](int n) {
    for (int i = 0; i < n; ++i) {
      const double t = time(rng);
      SceneFrame kept;
      {
        AnimationEndScope ends(d->project(), d.get(), d->revision());
        kept = evaluateScene(d->project(), ".", assets, t);
      }
      const uint64_t before = animationEndWalks();
      SceneFrame walked = evaluateScene(d->project(), ".", assets, t);  // no scope: walks, uncounted
      CHECK(animationEndWalks() == before);
      REQUIRE(kept.blobs.size() == 2);
      REQUIRE(walked.blobs.size() == 2);
      for (size_t b = 0; b < 2; ++b) CHECK(kept.blobs[b].treeTimeSec == walked.blobs[b].treeTimeSec);
    }
  };
  const uint64_t start = animationEndWalks();
  evaluateMany(40);
  CHECK(animationEndWalks() - start == 2);  // two looping trees, one revision
  auto c = setBlobParamCommand(d->project(), "blob", radius, 3.0, 0.6f, true);
  REQUIRE(c.ok());
  d->execute(std::move(*c));
  evaluateMany(40);
  CHECK(animationEndWalks() - start == 4);  // a new revision: each walked once more
  // A looping actor of another project (not the scope's) is walked, not looked up.
  Project other = d->project();
  {
    AnimationEndScope ends(d->project(), d.get(), d->revision());
    const uint64_t before = animationEndWalks();
    CHECK(blobActorTimeSec(other.actors[0], 3.5) == Approx(0.5));  // its tree ends at 3 s
    CHECK(animationEndWalks() == before);
  }
}
