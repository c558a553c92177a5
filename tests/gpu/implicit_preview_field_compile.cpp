// The GPU preview's field compiles off the UI thread (implicit_preview.h,
// preview_field_compiler.h), on lavapipe: a shape whose field takes long to
// compile does not hold up update(), the viewport keeps the last mesh until it
// is compiled, shapes superseded while waiting are never compiled, and a
// screenshot (settle) still shows exactly the shape asked for; fields of C(t) scrubbed refill the
// kept structure of the last one (counted).
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "gpu_fixture.h"
#include "gpu/polygonizer/implicit_preview.h"
#include "core/project/animorphosis_project.h"
#include "core/scene/animorphosis_preview_source.h"
#include "core/scene/morph_preview_source.h"
#include "demo/animorphosis_demo.h"
#include "util/morph_fixtures.h"

using namespace animorph;
using namespace animorph::gpu;

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

constexpr double kFieldSleepSec = 0.4;

// The demo morph's B->C stage at a time, whose field() takes kFieldSleepSec longer (a big tree's
// flattening) and counts its calls.
class SlowFieldSource final : public PreviewSource {
 public:
  explicit SlowFieldSource(std::shared_ptr<const PreviewSource> inner) : inner_(std::move(inner)) {}
  bool sameAs(const PreviewSource& other) const override {
    auto* o = dynamic_cast<const SlowFieldSource*>(&other);
    return o && inner_->sameAs(*o->inner_);
  }
  Status validate() const override { return inner_->validate(); }
  Result<PolygonizeResult> polygonize(int resolution, int threads, const std::atomic<bool>* cancel,
                                      PolygonizeHistory* history) const override {
    return inner_->polygonize(resolution, threads, cancel, history);
  }
  Result<PreviewField> field(int resolution) const override {
    ++calls_;
    std::this_thread::sleep_for(std::chrono::duration<double>(kFieldSleepSec));
    return inner_->field(resolution);
  }
  int fieldCalls() const { return calls_.load(); }

 private:
  std::shared_ptr<const PreviewSource> inner_;
  mutable std::atomic<int> calls_{0};
};

struct SlowStage {
  double t;
  std::shared_ptr<const SlowFieldSource> source;
};

struct Fixture {
  std::unique_ptr<Context> ctx = test::makeTestContext();
  std::shared_ptr<const MorphRuntime> rt = test::demoMorph().runtime;
  ImplicitPreviewSettings ps;
  Fixture() {
    ps.interactiveResolution = 24;
    ps.refinedResolution = 32;
    ps.gpu = true;
    ps.paceGpu = false;  // every frame may record: what is drawn depends on the fields alone
  }
  double at(double u) const {
    const MorphMarkers& mk = rt->setup.markers;
    return rt->timeline.frameToSec(int(mk.b + u * (mk.c - mk.b)));
  }
  SlowStage slow(double u) const { return {at(u), std::make_shared<SlowFieldSource>(morphPreviewSource(rt, at(u)))}; }
  // Frames of the editor's loop on one shape until the preview is idle.
  ImplicitPreviewStatus settle(ImplicitPreview& p, const std::shared_ptr<const PreviewSource>& source, double t) {
    for (int i = 0; i < 60 && (i == 0 || p.busy()); ++i) {
      p.update(source, t, ps);
      p.endFrame();
      p.waitIdle(60.0);
    }
    REQUIRE_FALSE(p.busy());
    return p.status();
  }
  // The triangles of the shape at t on a preview of its own, with a field of the usual cost.
  size_t trianglesAt(double t) {
    ImplicitPreview fast(*ctx);
    return settle(fast, morphPreviewSource(rt, t), t).triangles;
  }
};

}  // namespace

TEST_CASE("implicit preview: a slow field compiles off the UI thread and the shape appears once compiled",
          "[gpu][preview]") {
  Fixture f;
  ImplicitPreview preview(*f.ctx);
  const SlowStage first = f.slow(0.3);
  f.settle(preview, first.source, first.t);  // pipelines, buffers; the field's cost is known now
  REQUIRE(preview.status().gpu);
  REQUIRE(preview.status().timeSec == first.t);
  const PreviewFieldCounters before = preview.fieldCounters();

  const SlowStage next = f.slow(0.6);
  const auto start = Clock::now();
  preview.update(next.source, next.t, f.ps);
  CHECK(secondsSince(start) < kFieldSleepSec / 2);  // the frame did not wait for the field
  // Meanwhile the viewport draws the last mesh, and the preview asks for frames.
  CHECK(preview.status().timeSec == first.t);
  CHECK(preview.busy());
  CHECK(preview.needsFrames());
  Scene scene;
  preview.draw(scene, glm::mat4(1.0f), glm::vec4(1.0f), false);
  CHECK(scene.generatedMeshes.size() == 1);
  preview.endFrame();
  // The editor's loop goes on; the shape is drawn once its field is compiled.
  double slowestUpdate = 0.0;
  for (int i = 0; i < 300 && preview.status().timeSec != next.t; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto t = Clock::now();
    preview.update(next.source, next.t, f.ps);
    slowestUpdate = std::max(slowestUpdate, secondsSince(t));
    preview.endFrame();
  }
  CHECK(preview.status().timeSec == next.t);
  CHECK(secondsSince(start) >= kFieldSleepSec);
  CHECK(slowestUpdate < kFieldSleepSec / 2);
  const PreviewFieldCounters after = preview.fieldCounters();
  CHECK(after.onCompileThread > before.onCompileThread);
  CHECK(after.onCallerThread == before.onCallerThread);
  // Refined, it is the shape a preview with a fast field shows.
  const ImplicitPreviewStatus s = f.settle(preview, next.source, next.t);
  CHECK(s.gpu);
  CHECK(s.resolution == f.ps.refinedResolution);
  CHECK(s.triangles == f.trianglesAt(next.t));
  CHECK(f.ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: a shape superseded while its field waits is never compiled", "[gpu][preview]") {
  Fixture f;
  ImplicitPreview preview(*f.ctx);
  const SlowStage first = f.slow(0.2);
  f.settle(preview, first.source, first.t);
  const PreviewFieldCounters before = preview.fieldCounters();
  // Scrubbing three frames while the first new field compiles: the second waits, the third replaces it.
  const SlowStage a = f.slow(0.4), b = f.slow(0.5), c = f.slow(0.6);
  preview.update(a.source, a.t, f.ps);
  preview.endFrame();
  for (int i = 0; i < 500 && a.source->fieldCalls() == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  REQUIRE(a.source->fieldCalls() == 1);  // being compiled
  preview.update(b.source, b.t, f.ps);
  preview.endFrame();
  preview.update(c.source, c.t, f.ps);
  preview.endFrame();
  std::vector<double> drawn;
  for (int i = 0; i < 300 && (preview.busy() || preview.status().timeSec != c.t); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    preview.update(c.source, c.t, f.ps);
    preview.endFrame();
    drawn.push_back(preview.status().timeSec);
  }
  CHECK(drawn.back() == c.t);
  CHECK(b.source->fieldCalls() == 0);
  CHECK(std::find(drawn.begin(), drawn.end(), b.t) == drawn.end());
  // The field compiled when b came in was a newer shape than the one on screen: it was drawn.
  CHECK(std::find(drawn.begin(), drawn.end(), a.t) != drawn.end());
  CHECK(preview.fieldCounters().superseded > before.superseded);
  CHECK(f.ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: a screenshot shows the shape asked for while an older field compiles",
          "[gpu][preview]") {
  Fixture f;
  ImplicitPreview preview(*f.ctx);
  const SlowStage first = f.slow(0.2);
  f.settle(preview, first.source, first.t);
  const SlowStage older = f.slow(0.4), shot = f.slow(0.7);
  preview.update(older.source, older.t, f.ps);  // its field compiles on the thread
  preview.endFrame();
  ImplicitPreviewSettings settle = f.ps;
  settle.settle = true;
  preview.update(shot.source, shot.t, settle);
  ImplicitPreviewStatus s = preview.status();
  CHECK(s.timeSec == shot.t);
  CHECK(s.resolution == f.ps.refinedResolution);
  CHECK_FALSE(preview.busy());
  const uint64_t records = preview.gpuRecordCount();
  // The older field, finished afterwards, does not replace it.
  std::this_thread::sleep_for(std::chrono::duration<double>(1.5 * kFieldSleepSec));
  preview.endFrame();
  preview.update(shot.source, shot.t, f.ps);
  preview.endFrame();
  CHECK(preview.status().timeSec == shot.t);
  CHECK(preview.gpuRecordCount() == records);
  CHECK_FALSE(preview.busy());
  CHECK(s.triangles == f.trianglesAt(shot.t));
  CHECK(f.ctx->validationErrorCount() == 0);
}

TEST_CASE("preview field compiler: scrubbing C(t) refills the kept structure (counted), a new C compiles",
          "[gpu][preview][refill]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  auto tree = std::make_shared<const GenericTree>(std::move(*c));
  const AnimorphosisTiming timing = animorphosisTiming(*p);
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  PreviewFieldCompiler compiler;
  auto shared = std::make_shared<SharedGenericCompiler>(tree);
  for (int k = 0; k < 6; ++k) {
    const double t = mid + k / 30.0;
    auto r = compiler.compileHere(animorphosisPreviewSource(shared, timing, t), 48, t);
    REQUIRE(r);
    INFO(r->error);
    CHECK(r->field.has_value());
  }
  PreviewFieldCounters n = compiler.counters();
  INFO(n.refilled << " refilled, " << n.firstCompiles << " first, " << n.structureChanged << " changed, "
                  << n.notRefilled << " not refilled");
  CHECK(n.onCallerThread == 6);
  CHECK(n.firstCompiles == 1);
  CHECK(n.refilled >= 4);
  CHECK(n.refilled + n.firstCompiles + n.structureChanged == 6);
  // The fields' programs come from the shared compiler's pool: a frame's program is taken again
  // once no compiled field holds it (the compiler keeps the latest), not made anew each frame.
  const SharedGenericCompiler::PoolCounters pool = shared->poolCounters();
  INFO(pool.made << " programs made, " << pool.reused << " reused");
  CHECK(pool.made + pool.reused == 6);
  CHECK(pool.reused >= 3);
  {
    const double t = mid + 6 / 30.0;
    auto last = compiler.compileHere(animorphosisPreviewSource(shared, timing, t), 48, t);
    REQUIRE(last->field);
    CHECK(last->field->pooledProgram);
    // A reused program's mesh equals a fresh compile's, bit for bit.
    GenericProgramCompiler fresh(*tree);
    fresh.keepValues(false);
    FieldProgram ref;
    fresh.compile(timing, t, ref);
    auto mine = polygonizePreviewProgram(last->field->fieldProgram(), 24, 1, nullptr, nullptr);
    auto theirs = polygonizePreviewProgram(ref, 24, 1, nullptr, nullptr);
    REQUIRE(mine.ok());
    REQUIRE(theirs.ok());
    CHECK(mine->mesh.triangleCount() > 0);
    CHECK(mine->mesh == theirs->mesh);
  }
  // Another C (the editor builds one after an edit): its first field is compiled fully.
  auto edited = std::make_shared<SharedGenericCompiler>(tree);
  auto r = compiler.compileHere(animorphosisPreviewSource(edited, timing, mid), 48, mid);
  REQUIRE(r);
  CHECK(compiler.counters().firstCompiles == 2);
  CHECK(compiler.counters().refilled + compiler.counters().structureChanged ==
        n.refilled + n.structureChanged + 1);  // (the seventh frame above)
}

TEST_CASE("implicit preview: C(t) at 96^3 with the GPU preference draws a GPU mesh, not the CPU fallback, within 0.5 % "
          "of the CPU's triangles",
          "[gpu][preview][animorphosis]") {
  // lavapipe cuts a record's loops where the per-region lists of C(t) are longer than counted
  // (the coarse pass at 96^3); that record is redone with single-block lists, as polygonize() redoes
  // its frame, instead of sending the preview to the CPU worker for good (bench animorph-scrub --gpu).
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  auto shared = std::make_shared<SharedGenericCompiler>(std::make_shared<const GenericTree>(std::move(*c)));
  const AnimorphosisTiming timing = animorphosisTiming(*p);
  const double t = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  auto source = animorphosisPreviewSource(shared, timing, t);
  Fixture f;
  f.ps.interactiveResolution = 96;
  f.ps.refinedResolution = 96;
  ImplicitPreview preview(*f.ctx);
  const ImplicitPreviewStatus st = f.settle(preview, source, t);
  INFO("fell back: " << st.gpuFallback << "; " << preview.gpuRecordCount() << " records, "
                     << preview.gpuCutFramesRedone() << " cut and redone");
  CHECK(st.gpu);
  CHECK(st.gpuFallback.empty());
  CHECK(preview.gpuFailure().empty());
  CHECK(st.resolution == 96);
  auto cpu = source->polygonize(96, 0, nullptr, nullptr);
  REQUIRE(cpu.ok());
  const double cpuTris = double(cpu->mesh.triangleCount());
  REQUIRE(cpuTris > 1000);
  CHECK(std::abs(double(st.triangles) - cpuTris) <= 0.005 * cpuTris);
  CHECK(f.ctx->validationErrorCount() == 0);
}
