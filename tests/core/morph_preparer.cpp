// The editor's morph preparation off the UI thread (morph_preparer.h): the first call
// starts a job and shows nothing of another document; a new revision keeps showing the previous
// runtime until its job finishes; the result equals a synchronous prepareMorph; errors and
// disabled morphs come back as such; the job's loaded characters end up in the caller's cache.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "core/scene/morph_runtime.h"
#include "editor/morph_preparer.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

// Calls update() until no job runs (bounded), returning the last result.
std::shared_ptr<const MorphRuntime> settle(MorphPreparer& mp, const Project& p, AssetCache& assets, const void* owner,
                                           uint64_t revision) {
  auto rt = mp.update(p, test::demoMorph().dir, assets, owner, revision);
  for (int i = 0; i < 3000 && mp.preparing(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    rt = mp.update(p, test::demoMorph().dir, assets, owner, revision);
  }
  REQUIRE_FALSE(mp.preparing());
  return rt;
}

}  // namespace

TEST_CASE("morph preparer: prepares off the calling thread and keeps the previous runtime meanwhile", "[morph]") {
  const test::DemoMorph& demo = test::demoMorph();
  MorphPreparer mp;
  AssetCache assets;
  int docA = 0, docB = 0;  // two documents, told apart by address

  // First call: a job starts; nothing to show yet for this document.
  auto first = mp.update(demo.project, demo.dir, assets, &docA, 1);
  CHECK(mp.preparing());
  CHECK(first == nullptr);
  auto rt1 = settle(mp, demo.project, assets, &docA, 1);
  REQUIRE(rt1);
  CHECK(mp.error().empty());
  // Same as preparing on this thread.
  AssetCache direct;
  auto sync = prepareMorph(demo.project, demo.dir, direct);
  REQUIRE(sync.ok());
  CHECK((*sync)->setup == rt1->setup);
  CHECK((*sync)->source.vertexCount == rt1->source.vertexCount);
  CHECK((*sync)->target.vertexCount == rt1->target.vertexCount);
  // The job's characters were merged into the caller's cache.
  CHECK(assets.entries().size() == direct.entries().size());

  // Up to date: no job, the same runtime.
  CHECK(mp.update(demo.project, demo.dir, assets, &docA, 1) == rt1);
  CHECK_FALSE(mp.preparing());

  // A new revision: the previous runtime stays on screen while the job runs.
  Project edited = demo.project;
  edited.morph.markers.c += 1;
  auto during = mp.update(edited, demo.dir, assets, &docA, 2);
  CHECK(mp.preparing());
  CHECK(during == rt1);
  auto rt2 = settle(mp, edited, assets, &docA, 2);
  REQUIRE(rt2);
  CHECK(rt2 != rt1);
  CHECK(rt2->setup.markers.c == edited.morph.markers.c);

  // Another document never sees this one's runtime.
  CHECK(mp.update(demo.project, demo.dir, assets, &docB, 1) == nullptr);
  auto rtB = settle(mp, demo.project, assets, &docB, 1);
  CHECK(rtB);

  // wait(): up to date at once.
  auto waited = mp.wait(edited, demo.dir, assets, &docB, 7);
  REQUIRE(waited);
  CHECK_FALSE(mp.preparing());
  CHECK(waited->setup.markers.c == edited.morph.markers.c);
}

TEST_CASE("morph preparer: a failed preparation gives its error and no runtime, no morph gives null", "[morph]") {
  const test::DemoMorph& demo = test::demoMorph();
  MorphPreparer mp;
  AssetCache assets;
  int doc = 0;
  Project broken = demo.project;
  for (Actor& a : broken.actors)
    if (a.id == broken.morph.targetActorId) a.assetPath = "no_such_file.glb";
  auto rt = settle(mp, broken, assets, &doc, 1);
  CHECK(rt == nullptr);
  CHECK(mp.error().find("no_such_file.glb") != std::string::npos);

  Project none = demo.project;
  none.morph.sourceActorId.clear();
  CHECK(mp.update(none, demo.dir, assets, &doc, 2) == nullptr);
  CHECK_FALSE(mp.preparing());
  CHECK(mp.error().empty());
}
