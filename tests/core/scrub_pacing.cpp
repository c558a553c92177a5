#include <catch2/catch.hpp>

#include "demo/blob_creature.h"
#include "core/poly/preview_polygonizer.h"
#include "core/scene/scrub_pacing.h"

using namespace animorph;

TEST_CASE("scrub pacing: a new mesh is drawn at once, input once an interval, nothing waits", "[pacing]") {
  CHECK(ScrubPacer::intervalFor(24.0) == Approx(1.0 / 24.0));
  CHECK(ScrubPacer::intervalFor(30.0) == Approx(1.0 / 30.0));
  CHECK(ScrubPacer::intervalFor(240.0) == Approx(1.0 / 60.0));  // no faster than 60 frames a second
  CHECK(ScrubPacer::intervalFor(8.0) == Approx(1.0 / 24.0));    // input waits at most a 24th of a second
  CHECK(ScrubPacer::intervalFor(0.0) == Approx(1.0 / 24.0));

  CHECK(ScrubPacer::applies(true, true, false));
  CHECK_FALSE(ScrubPacer::applies(false, true, false));  // not scrubbing (orbiting, dragging a slider)
  CHECK_FALSE(ScrubPacer::applies(true, false, false));  // the worker is idle: draw input at once
  CHECK_FALSE(ScrubPacer::applies(true, true, true));    // playback, the GPU polygoniser, particles

  ScrubPacer p(0.04);
  p.frameStarted(10.0, 5, 7);
  // Nothing happened: wait (a frame all the same after kMaxWaitSec).
  CHECK(p.waitSec(10.02, 5, 7) == Approx(ScrubPacer::kMaxWaitSec - 0.02));
  CHECK(p.waitSec(10.0 + ScrubPacer::kMaxWaitSec + 0.001, 5, 7) == 0.0);
  // The cursor moved: drawn when the interval is up, not before.
  CHECK(p.waitSec(10.01, 6, 7) == Approx(0.03));
  CHECK(p.waitSec(10.04, 9, 7) == 0.0);
  CHECK(p.waitSec(10.2, 9, 7) == 0.0);
  // A new preview mesh: drawn at once, input or not.
  CHECK(p.waitSec(10.001, 5, 8) == 0.0);
  CHECK(p.waitSec(10.001, 6, 8) == 0.0);
  // The next frame counts from its own start.
  p.frameStarted(10.3, 9, 8);
  CHECK(p.waitSec(10.31, 10, 8) == Approx(0.03));
}

TEST_CASE("scrub pacing: a paced wait wakes when the preview worker publishes a mesh", "[pacing][preview]") {
  auto tree = std::make_shared<const BlobTree>(makeBlobCreature());
  PreviewPolygonizer worker(1);
  // No worker runs: the wait times out and says so.
  uint64_t seen = PreviewPolygonizer::publishedTotal();
  CHECK_FALSE(PreviewPolygonizer::waitForPublish(seen, 0.05));

  ScrubPacer pacer(1.0 / 24.0);
  pacer.frameStarted(0.0, 0, seen);
  PreviewRequest r;
  r.tree = tree;
  r.timeSec = 0.25;
  r.coarseResolution = 24;
  r.fineResolution = 24;
  r.threads = 2;  // this request's threads, not the worker's
  worker.submit(r);
  REQUIRE(PreviewPolygonizer::waitForPublish(seen, 60.0));
  const uint64_t now = PreviewPolygonizer::publishedTotal();
  CHECK(now == seen + 1);
  CHECK(pacer.waitSec(0.001, 0, now) == 0.0);  // the loop draws the new mesh at once
  REQUIRE(worker.waitIdle(60.0));
  auto latest = worker.latest();
  REQUIRE(latest);
  CHECK(latest->error.empty());
  CHECK(latest->mesh.triangleCount() > 0);
}
