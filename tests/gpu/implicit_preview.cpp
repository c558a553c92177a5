// The editor's implicit preview on lavapipe (implicit_preview.h): the GPU path
// of the morph's B->C stage gives the CPU's surface, GPU failures (a device
// out of memory, a field the GPU cannot express) fall back to the CPU worker
// with a message, and slow frames pace the GPU path. Validation on, no errors.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "gpu_fixture.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/polygonizer/implicit_preview.h"
#include "core/blobtree/blob_tree.h"
#include "core/standin_morph/mesh_distance.h"
#include "core/poly/mesh_checks.h"
#include "core/scene/morph_preview_source.h"
#include "util/morph_fixtures.h"

using namespace animorph;
using namespace animorph::gpu;

namespace {

double midStageSec(const MorphRuntime& rt, double u) {
  const MorphMarkers& mk = rt.setup.markers;
  return rt.timeline.frameToSec(int(mk.b + u * (mk.c - mk.b)));
}

// Frames of the editor's loop on one time until the preview settles.
ImplicitPreviewStatus settle(ImplicitPreview& p, const std::shared_ptr<const PreviewSource>& source, double t,
                             const ImplicitPreviewSettings& s) {
  for (int i = 0; i < 40; ++i) {
    p.update(source, t, s);
    p.endFrame();
    if (!p.busy()) break;
    p.waitIdle(60.0);
  }
  REQUIRE(p.waitIdle(60.0));
  return p.status();
}

// A fresh context and the demo morph's B->C stage at progress u: its time and preview source.
struct DemoStage {
  std::unique_ptr<Context> ctx;
  std::shared_ptr<const MorphRuntime> rt;
  double t;
  std::shared_ptr<const PreviewSource> source;
};
DemoStage demoStage(double u) {
  DemoStage d{test::makeTestContext(), test::demoMorph().runtime, 0.0, nullptr};
  d.t = midStageSec(*d.rt, u);
  d.source = morphPreviewSource(d.rt, d.t);
  return d;
}

// GPU preview settings at the two resolutions.
ImplicitPreviewSettings gpuSettings(int interactive, int refined) {
  ImplicitPreviewSettings ps;
  ps.interactiveResolution = interactive;
  ps.refinedResolution = refined;
  ps.gpu = true;
  return ps;
}

// What the preview hands the GPU at res: its field and the settings with the field's bounds.
struct PreviewGpuField {
  PreviewField field;
  GpuPolygonizeSettings settings;
};
PreviewGpuField previewGpuField(const PreviewSource& source, int res) {
  auto field = source.field(res);
  INFO(field.error());
  REQUIRE(field.ok());
  PreviewGpuField f{std::move(*field), {}};
  f.settings.resolution = res;
  f.settings.bounds = f.field.bounds;
  f.settings.noiseAmplitude = f.field.noiseAmplitude;
  f.settings.noiseFrequency = f.field.noiseFrequency;
  return f;
}

// The field the preview hands the GPU at res, polygonised and read back, against the CPU stage
// mesh: triangle counts within 0.5 %, vertices within 0.05 cell both ways. The CPU's mesh.
PolygonizeResult gpuFieldMatchesCpu(Context& ctx, const PreviewSource& source, int res) {
  const PreviewGpuField pf = previewGpuField(source, res);
  auto poly = GpuPolygonizer::create(ctx);
  REQUIRE(poly.ok());
  auto st = (*poly)->polygonize(GpuField::single(pf.field.fieldProgram()), pf.settings);
  INFO(st.error());
  REQUIRE(st.ok());
  auto gpuMesh = (*poly)->readBack();
  REQUIRE(gpuMesh.ok());
  auto cpu = source.polygonize(res, 0, nullptr, nullptr);
  REQUIRE(cpu.ok());
  const double cpuTris = double(cpu->mesh.triangleCount());
  REQUIRE(cpuTris > 100);
  CHECK(std::abs(double(gpuMesh->triangleCount()) - cpuTris) <= 0.005 * cpuTris);
  const float cell = cpu->stats.cellSize;
  CHECK(pointsToMeshDistance(gpuMesh->positions, cpu->mesh).maxDistance < 0.05 * cell);
  CHECK(pointsToMeshDistance(cpu->mesh.positions, *gpuMesh).maxDistance < 0.05 * cell);
  return std::move(*cpu);
}

// A preview settled on the GPU path with `triangles`, and no validation error.
void checkOnGpu(const ImplicitPreviewStatus& s, size_t triangles, const Context& ctx) {
  INFO(s.gpuFallback);
  CHECK(s.gpu);
  CHECK(s.gpuFallback.empty());
  CHECK(s.triangles == triangles);
  CHECK(ctx.validationErrorCount() == 0);
}

}  // namespace

TEST_CASE("implicit preview: the GPU path of the morph stage matches the CPU mesh", "[gpu][preview]") {
  auto [ctx, rt, t, source] = demoStage(0.5);
  const int res = 48;

  const double cpuTris = double(gpuFieldMatchesCpu(*ctx, *source, res).mesh.triangleCount());

  // The preview itself on the GPU path: its own submissions, the draw, the same triangle count.
  ImplicitPreview preview(*ctx);
  ImplicitPreviewSettings ps = gpuSettings(32, res);
  ImplicitPreviewStatus s = settle(preview, source, t, ps);
  INFO(s.gpuFallback);
  CHECK(s.gpuFallback.empty());
  CHECK(s.gpu);
  CHECK(s.hasMesh);
  CHECK(s.resolution == res);
  CHECK_FALSE(s.refining);
  CHECK(std::abs(double(s.triangles) - cpuTris) <= 0.005 * cpuTris);
  // One record: the first frame compiled the pipelines (the CPU worker drew), the next recorded
  // the shape at the refined resolution, and that record's own counters settled it once it had
  // completed, with no more records to find out whether it fitted (there were three).
  CHECK(preview.gpuRecordCount() == 1);
  preview.update(source, t, ps);  // quiet
  CHECK(preview.gpuRecordCount() == 1);
  Scene scene;
  preview.draw(scene, glm::mat4(1.0f), glm::vec4(1.0f), false);
  CHECK(scene.generatedMeshes.size() == 1);
  CHECK(scene.meshes.empty());
  CHECK(preview.cpuResult() == nullptr);
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: a GPU out of memory falls back to the CPU worker with a message", "[gpu][preview]") {
  auto [ctx, rt, t, source] = demoStage(0.3);
  ImplicitPreviewSettings ps = gpuSettings(24, 40);
  ImplicitPreview preview(*ctx);
  ::setenv("ANIMORPH_DEBUG_GPU_BUFFER_LIMIT_KB", "16", 1);
  preview.update(source, t, ps);
  ::unsetenv("ANIMORPH_DEBUG_GPU_BUFFER_LIMIT_KB");
  INFO(preview.gpuFailure());
  CHECK(preview.gpuFailure().find("VK_ERROR_OUT_OF_DEVICE_MEMORY") != std::string::npos);
  ImplicitPreviewStatus s = settle(preview, source, t, ps);
  CHECK_FALSE(s.gpu);
  CHECK(s.hasMesh);
  CHECK(s.error.empty());
  CHECK(s.resolution == 40);
  CHECK(s.triangles > 100);
  CHECK(s.gpuFallback == preview.gpuFailure());
  CHECK(describePreviewStatus(s, {true, "GPU (preference)"}).find("using the CPU") != std::string::npos);
  auto r = preview.cpuResult();
  REQUIRE(r);
  CHECK(r->mesh.triangleCount() == s.triangles);
  // The failure sticks for this preview until cleared (the user switching devices); then the GPU works again.
  preview.update(source, t, ps);
  CHECK_FALSE(preview.status().gpu);
  preview.clearGpuFailure();
  checkOnGpu(settle(preview, source, t, ps), r->mesh.triangleCount(), *ctx);
}

TEST_CASE("implicit preview: a stage with solid noise is displaced on the GPU as on the CPU", "[gpu][preview]") {
  // The noise track used to send the stage to the CPU worker ("solid noise is applied on the CPU
  // only"); the GPU path now displaces the vertices in a pass of its own.
  auto ctx = test::makeTestContext();
  auto noisy = std::make_shared<MorphRuntime>(*test::demoMorph().runtime);
  noisy->setup.noiseAmplitude = FloatTrack(0.05f);
  noisy->setup.noiseFrequency = 4.0f;
  const double t = midStageSec(*noisy, 0.5);
  const auto source = morphPreviewSource(noisy, t);
  const int res = 48;
  REQUIRE(previewGpuField(*source, res).field.noiseAmplitude == 0.05f);
  const PolygonizeResult cpu = gpuFieldMatchesCpu(*ctx, *source, res);  // CPU: polygonised, then displaced
  CHECK(0.05f > cpu.stats.cellSize);  // a displacement the comparison sees
  ImplicitPreview preview(*ctx);
  checkOnGpu(settle(preview, source, t, gpuSettings(24, res)), cpu.mesh.triangleCount(), *ctx);
}

TEST_CASE("implicit preview: a shape the GPU cannot express is polygonised on the CPU", "[gpu][preview]") {
  // Differences nested 20 deep in their subtracted operand (a bead minus the next difference):
  // the operand order is the operator's meaning, so 21 values wait on the operand stack, beyond
  // the GPU interpreter's 16 (blends and unions nested so are reordered: field_program tests).
  auto ctx = test::makeTestContext();
  auto tree = std::make_shared<BlobTree>();
  tree->threshold = FloatTrack(0.5f);
  int id = 1;
  BlobNode inner = makeBlobNode(NodeType::Point, id++);
  inner.floatParam("radius") = FloatTrack(0.2f);
  for (int i = 0; i < 20; ++i) {
    BlobNode bead = makeBlobNode(NodeType::Point, id++);
    bead.vec3Param("center") = Vec3Track(glm::vec3(0.05f * float(i + 1), 0.0f, 0.0f));
    bead.floatParam("radius") = FloatTrack(0.2f);
    BlobNode difference = makeBlobNode(NodeType::Difference, id++);
    difference.children = {bead, inner};
    inner = difference;
  }
  tree->root = inner;
  ImplicitPreview preview(*ctx);
  ImplicitPreviewStatus s = settle(preview, blobTreePreviewSource(tree, 0.0), 0.0, gpuSettings(24, 32));
  CHECK_FALSE(s.gpu);
  INFO(s.gpuFallback);
  CHECK(s.gpuFallback.find("stack depth 21") != std::string::npos);
  CHECK(preview.gpuFailure().empty());  // only this shape: not a sticky failure
  CHECK(s.triangles > 100);
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: after a slow frame that polygonised, the next new shape waits a frame (GPU pacing)",
          "[gpu][preview]") {
  auto ctx = test::makeTestContext();
  const auto rt = test::demoMorph().runtime;
  ImplicitPreviewSettings ps = gpuSettings(24, 32);
  const double t0 = midStageSec(*rt, 0.2);
  for (bool pace : {true, false}) {
    ps.paceGpu = pace;
    ImplicitPreview preview(*ctx);
    settle(preview, morphPreviewSource(rt, t0), t0, ps);  // pipelines compiled, buffers grown
    REQUIRE(preview.status().gpu);
    REQUIRE(preview.status().timeSec == t0);
    // Scrubbing with frames slower than 1/30 s: each frame a new time.
    std::vector<double> drawn;
    bool busyWhileWaiting = true;
    for (int i = 1; i <= 6; ++i) {
      const double t = midStageSec(*rt, 0.2 + 0.1 * i);
      preview.update(morphPreviewSource(rt, t), t, ps);
      drawn.push_back(preview.status().timeSec);
      if (drawn.back() != t) busyWhileWaiting = busyWhileWaiting && preview.busy();
      preview.endFrame();
      preview.waitIdle(60.0);
      std::this_thread::sleep_for(std::chrono::milliseconds(45));
    }
    INFO("pacing " << pace);
    int recorded = 0;
    for (int i = 1; i <= 6; ++i) recorded += drawn[size_t(i - 1)] == midStageSec(*rt, 0.2 + 0.1 * i);
    if (pace) {
      // Every other frame polygonises; the others keep drawing the mesh before.
      CHECK(recorded == 3);
      for (int i = 2; i <= 6; i += 2) CHECK(drawn[size_t(i - 1)] == drawn[size_t(i - 2)]);
      CHECK(busyWhileWaiting);  // a shape is waiting: the preview is not idle
    } else {
      CHECK(recorded == 6);
    }
    // Scrubbing stops: the last time is polygonised and drawn.
    const double tEnd = midStageSec(*rt, 0.8);
    ImplicitPreviewStatus s = settle(preview, morphPreviewSource(rt, tEnd), tEnd, ps);
    CHECK(s.timeSec == tEnd);
    CHECK(s.resolution == ps.refinedResolution);
  }
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: while dragging, a repeated shape is refined once it has held still (at once on a GPU)",
          "[gpu][preview]") {
  // A mouse that pauses for a frame mid-drag repeats the shape: refining it at once started a
  // refined polygonisation the next frames waited for (on lavapipe the frame shares the queue).
  auto ctx = test::makeTestContext();
  const auto rt = test::demoMorph().runtime;
  ImplicitPreviewSettings ps = gpuSettings(24, 32);
  ps.paceGpu = false;
  ImplicitPreview preview(*ctx);
  // One editor frame at progress u; `wait`: then until the GPU has finished it.
  auto frame = [&](double u, bool wait) {
    const double t = midStageSec(*rt, u);
    preview.update(morphPreviewSource(rt, t), t, ps);
    preview.endFrame();
    if (wait) preview.waitIdle(60.0);
    return preview.status();
  };
  settle(preview, morphPreviewSource(rt, midStageSec(*rt, 0.2)), midStageSec(*rt, 0.2), ps);  // pipelines, buffers
  // Dragging: a new shape every frame, then the mouse pauses for a frame.
  for (double u : {0.25, 0.3, 0.35, 0.4}) CHECK(frame(u, true).resolution == ps.interactiveResolution);
  const uint64_t records = preview.gpuRecordCount();
  if (ctx->deviceType() == VK_PHYSICAL_DEVICE_TYPE_CPU) {
    CHECK(frame(0.4, false).resolution == ps.interactiveResolution);
    CHECK(preview.gpuRecordCount() == records);  // held: no refined record
    CHECK(preview.busy());                        // and the editor keeps drawing frames
  } else {
    // On a GPU a refined record takes milliseconds: the repeated shape is refined at once.
    frame(0.4, false);
    CHECK(preview.gpuRecordCount() == records + 1);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ImplicitPreviewStatus s = settle(preview, morphPreviewSource(rt, midStageSec(*rt, 0.4)), midStageSec(*rt, 0.4), ps);
  CHECK(s.resolution == ps.refinedResolution);  // held still: refined
  // A single step after a pause (an arrow key): the repeated shape is refined at once.
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  CHECK(frame(0.45, true).resolution == ps.interactiveResolution);
  CHECK(frame(0.45, true).resolution == ps.refinedResolution);
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: a new kind of shape compiles its GPU pipelines without stalling the frame",
          "[gpu][preview]") {
  auto [ctx, rt, t, source] = demoStage(0.5);
  ImplicitPreviewSettings ps = gpuSettings(32, 40);

  // The first frame starts the compilation and hands the shape to the CPU worker: nothing
  // recorded, nothing to draw yet, the status bar says why, and the preview asks for more frames.
  ImplicitPreview preview(*ctx);
  preview.update(source, t, ps);
  preview.endFrame();
  ImplicitPreviewStatus first = preview.status();
  CHECK(first.compiling);
  CHECK_FALSE(first.hasMesh);
  CHECK(preview.busy());
  CHECK(preview.needsFrames());
  CHECK_THAT(describePreviewStatus(first, {true, "GPU"}), Catch::Contains("compiling"));
  Scene none;
  preview.draw(none, glm::mat4(1.0f), glm::vec4(1.0f), false);
  CHECK(none.generatedMeshes.empty());
  CHECK(none.meshes.empty());
  // Until the pipelines are there the viewport shows the worker's mesh of this shape.
  preview.waitIdle(60.0);
  ImplicitPreviewStatus filled = preview.status();
  CHECK(filled.compiling);
  CHECK(filled.hasMesh);
  CHECK_FALSE(filled.gpu);
  CHECK(filled.resolution == ps.refinedResolution);
  CHECK(filled.triangles > 100);
  CHECK(filled.timeSec == t);
  CHECK_THAT(describePreviewStatus(filled, {true, "GPU"}), Catch::Contains("CPU") && Catch::Contains("compiling"));
  Scene cpuDrawn;
  preview.draw(cpuDrawn, glm::mat4(1.0f), glm::vec4(1.0f), false);
  CHECK(cpuDrawn.meshes.size() == 1);
  CHECK(cpuDrawn.generatedMeshes.empty());
  REQUIRE(preview.cpuResult() != nullptr);
  // Frames go on; once the pipelines are there the GPU draws the shape, refined, and the worker's
  // mesh is gone.
  ImplicitPreviewStatus s = settle(preview, source, t, ps);
  CHECK_FALSE(s.compiling);
  CHECK(s.hasMesh);
  CHECK(s.gpu);
  CHECK(s.resolution == ps.refinedResolution);
  CHECK(s.triangles > 100);
  CHECK(std::abs(double(s.triangles) - double(filled.triangles)) <= 0.005 * double(filled.triangles));
  Scene gpuDrawn;
  preview.draw(gpuDrawn, glm::mat4(1.0f), glm::vec4(1.0f), false);
  CHECK(gpuDrawn.generatedMeshes.size() == 1);
  CHECK(gpuDrawn.meshes.empty());
  CHECK(preview.cpuResult() == nullptr);

  // A screenshot (settle) shows the whole shape in its own frame: on a fresh preview it waits for
  // the pipelines and polygonises until the mesh fits (a first record would overflow the initial
  // buffers and draw nothing until a later frame), so the very first frame has the refined mesh.
  ImplicitPreview shot(*ctx);
  ps.settle = true;
  shot.update(source, t, ps);
  ImplicitPreviewStatus now = shot.status();
  CHECK_FALSE(now.compiling);
  CHECK(now.hasMesh);
  CHECK(now.resolution == ps.refinedResolution);
  CHECK(now.triangles == s.triangles);
  CHECK_FALSE(shot.busy());
  Scene drawn;
  shot.draw(drawn, glm::mat4(1.0f), glm::vec4(1.0f), false);
  CHECK(drawn.generatedMeshes.size() == 1);
  shot.endFrame();
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: the first GPU record of a shape fits its buffers (no blank frames)", "[gpu][preview]") {
  // The preview's bounds hug the shape, so most of the grid's blocks hold surface. A record reads
  // its counters kFramesInFlight records later: if the first one overflowed its initial buffers it
  // would draw nothing, and the viewport would flash empty when the preview first appears.
  auto ctx = test::makeTestContext();
  const auto rt = test::demoMorph().runtime;
  for (double u : {0.1, 0.5, 0.9}) {
    const double t = midStageSec(*rt, u);
    auto source = morphPreviewSource(rt, t);
    for (int res : {96, 128}) {
      const PreviewGpuField pf = previewGpuField(*source, res);
      auto poly = GpuPolygonizer::create(*ctx);
      REQUIRE(poly.ok());
      const GpuField gf = GpuField::single(pf.field.fieldProgram());
      for (uint64_t serial : {uint64_t(0), uint64_t(kFramesInFlight)}) {
        Status recorded;
        Status submitted = ctx->submitImmediate([&](VkCommandBuffer cmd) { recorded = (*poly)->record(cmd, serial, gf, pf.settings); });
        INFO(recorded.error() + submitted.error());
        REQUIRE(recorded.ok());
        REQUIRE(submitted.ok());
      }
      // The second record read the first one's counters.
      INFO("u " << u << ", " << res << "^3: " << (*poly)->lastStats().blocksActive << " active blocks");
      CHECK_FALSE((*poly)->lastStats().overflowed);
      CHECK((*poly)->lastStats().triangles > 1000);
    }
  }
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: the transitions' stand-in core on the GPU matches the CPU mesh", "[gpu][preview]") {
  auto ctx = test::makeTestContext();
  const std::shared_ptr<const MorphRuntime> rt = test::demoMorph().runtime;
  const MorphMarkers& mk = rt->setup.markers;
  // The expansion a third in (the core scaled down, under its bound) and the collapse two thirds in.
  const auto expanding = standinCorePreviewSource(rt, rt->timeline.frameToSec(mk.c + (mk.d - mk.c) / 3), true, 1.0 / 3.0);
  const auto collapsing = standinCorePreviewSource(rt, rt->timeline.frameToSec(mk.a + 2 * (mk.b - mk.a) / 3), false, 2.0 / 3.0);
  gpuFieldMatchesCpu(*ctx, *expanding, 48);
  gpuFieldMatchesCpu(*ctx, *collapsing, 48);
  // A source is the same as another on the same runtime, time, side and progress only.
  CHECK(expanding->sameAs(*standinCorePreviewSource(rt, rt->timeline.frameToSec(mk.c + (mk.d - mk.c) / 3), true, 1.0 / 3.0)));
  CHECK_FALSE(expanding->sameAs(*collapsing));
  // Melted away at the end of the expansion: no field, said so.
  auto gone = standinCorePreviewSource(rt, rt->timeline.frameToSec(mk.d), true, 1.0)->field(48);
  REQUIRE_FALSE(gone.ok());
  CHECK(gone.error() == "the stand-in core has melted away at this time");
  CHECK(ctx->validationErrorCount() == 0);
}
