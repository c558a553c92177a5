// The morph's B->C stage on the preview worker (scene/morph_preview_source.h):
// the worker's answer is what evaluateMorphFrame gives at the same resolution,
// newer times supersede older ones, a newer request cancels the run in
// progress, the refined answer follows once the time stops changing, and the
// one-program field (the GPU's input) is the same surface.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "core/standin_morph/mesh_distance.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "core/scene/morph_preview_source.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

double midStageSec(const MorphRuntime& rt, double u = 0.5) {
  const MorphMarkers& mk = rt.setup.markers;
  return rt.timeline.frameToSec(int(mk.b + u * (mk.c - mk.b)));
}

PreviewRequest morphRequest(const std::shared_ptr<const MorphRuntime>& rt, double t, int coarse, int fine) {
  PreviewRequest r;
  r.source = morphPreviewSource(rt, t);
  r.timeSec = t;
  r.coarseResolution = coarse;
  r.fineResolution = fine;
  return r;
}

}  // namespace

TEST_CASE("morph preview: the worker's answer equals evaluateMorphFrame at the same resolution", "[morph][preview]") {
  const auto rt = test::demoMorph().runtime;
  const double t = midStageSec(*rt);
  PreviewPolygonizer worker(2);
  worker.submit(morphRequest(rt, t, 24, 40));
  REQUIRE(worker.waitIdle(120.0));
  auto r = worker.latest();
  REQUIRE(r);
  INFO(r->error);
  REQUIRE(r->error.empty());
  CHECK(r->final);
  CHECK(r->resolution == 40);
  CHECK(r->timeSec == t);

  MorphFrameSettings fs;
  fs.resolution = 40;
  fs.threads = 2;
  auto direct = evaluateMorphFrame(*rt, t, fs);
  REQUIRE(direct.ok());
  REQUIRE(direct->stage == MorphStage::Morph);
  REQUIRE(direct->mesh.triangleCount() > 100);
  CHECK(r->mesh.triangleCount() == direct->mesh.triangleCount());
  CHECK(meshVolume(r->mesh) == Approx(meshVolume(direct->mesh)).epsilon(1e-5));
  CHECK(pointsToMeshDistance(r->mesh.positions, direct->mesh).maxDistance < 1e-5);
}

TEST_CASE("morph preview: the coarse answer comes first, the refined one once the time stays", "[morph][preview]") {
  const auto rt = test::demoMorph().runtime;
  PreviewPolygonizer worker(2);
  const uint64_t id = worker.submit(morphRequest(rt, midStageSec(*rt), 24, 48));
  // The same time again is the same request: nothing restarts.
  CHECK(worker.submit(morphRequest(rt, midStageSec(*rt), 24, 48)) == id);
  REQUIRE(worker.waitIdle(120.0));
  const PreviewCounters c = worker.counters();
  CHECK(c.runsStarted == 2);
  CHECK(c.published == 2);
  auto r = worker.latest();
  REQUIRE(r);
  CHECK(r->resolution == 48);
  CHECK(r->final);
  CHECK(r->stats.cellSize > 0.0f);
}

TEST_CASE("morph preview: scrubbing supersedes older times and cancels runs in progress", "[morph][preview]") {
  const auto rt = test::demoMorph().runtime;
  PreviewPolygonizer worker(1);
  // A slow refined level so that newer times arrive while it runs: each newer time is sent once
  // the worker has begun both levels of the one before (or finished it), whatever the machine's load.
  double lastTime = 0.0;
  for (int i = 0; i < 12; ++i) {
    lastTime = midStageSec(*rt, 0.1 + 0.07 * i);
    const uint64_t started = worker.counters().runsStarted;
    worker.submit(morphRequest(rt, lastTime, 32, 160));
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (worker.counters().runsStarted < started + 2 && worker.busy() && std::chrono::steady_clock::now() < giveUp)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  REQUIRE(worker.waitIdle(240.0));
  const PreviewCounters c = worker.counters();
  CHECK(c.runsCancelled >= 1);
  CHECK(c.published < 24);  // not every time was answered at both levels
  auto r = worker.latest();
  REQUIRE(r);
  CHECK(r->timeSec == lastTime);  // the newest time wins
  CHECK(r->final);
  CHECK(r->resolution == 160);
}

TEST_CASE("morph preview: the one-program field is the stage's surface and carries the solid noise", "[morph][preview]") {
  const auto rt = test::demoMorph().runtime;
  const double t = midStageSec(*rt, 0.4);
  auto source = morphPreviewSource(rt, t);
  auto field = source->field(40);
  INFO(field.error());
  REQUIRE(field.ok());
  PolygonizeSettings ps;
  ps.resolution = 40;
  ps.bounds = field->bounds;
  auto one = polygonize(field->program, ps);
  REQUIRE(one.ok());
  auto viaSource = source->polygonize(40, 0, nullptr, nullptr);
  REQUIRE(viaSource.ok());
  CHECK(one->mesh.triangleCount() == viaSource->mesh.triangleCount());
  CHECK(one->mesh.triangleCount() > 100);

  auto noisy = std::make_shared<MorphRuntime>(*rt);
  noisy->setup.noiseAmplitude = FloatTrack(0.02f);
  noisy->setup.noiseFrequency = 6.0f;
  // The noise is the GPU's pass after the normals: the same program, the amplitude and frequency beside it.
  auto noisyField = morphPreviewSource(noisy, t)->field(40);
  REQUIRE(noisyField.ok());
  CHECK(noisyField->noiseAmplitude == Approx(0.02f));
  CHECK(noisyField->noiseFrequency == Approx(6.0f));
  CHECK(noisyField->program.ops.size() == field->program.ops.size());
  CHECK(field->noiseAmplitude == 0.0f);
  // Sources are the same only for the same runtime and time.
  CHECK(source->sameAs(*morphPreviewSource(rt, t)));
  CHECK_FALSE(source->sameAs(*morphPreviewSource(rt, t + 0.01)));
  CHECK_FALSE(source->sameAs(*morphPreviewSource(noisy, t)));
}
