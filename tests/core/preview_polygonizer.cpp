#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "core/blobtree/compile.h"
#include "core/blobtree/tree_edit.h"
#include "demo/blob_creature.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/preview_polygonizer.h"

using namespace animorph;

namespace {
std::shared_ptr<const BlobTree> creature() { return std::make_shared<const BlobTree>(makeBlobCreature()); }

PreviewRequest request(std::shared_ptr<const BlobTree> tree, double t, int coarse, int fine) {
  PreviewRequest r;
  r.tree = std::move(tree);
  r.timeSec = t;
  r.coarseResolution = coarse;
  r.fineResolution = fine;
  return r;
}

// Polls until pred holds (bounded, so a broken worker fails instead of hanging).
template <class Pred>
bool eventually(Pred pred, double seconds = 60.0) {
  auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!pred()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}
}  // namespace

TEST_CASE("preview: a request is answered coarse first, then fine", "[poly][preview]") {
  PreviewPolygonizer p(2);
  CHECK(p.latest() == nullptr);
  uint64_t id = p.submit(request(creature(), 0.5, 16, 40));
  CHECK(id == 1);
  REQUIRE(p.waitIdle(60.0));
  auto r = p.latest();
  REQUIRE(r);
  CHECK(r->requestId == id);
  CHECK(r->final);
  CHECK(r->resolution == 40);
  CHECK(r->error.empty());
  CHECK(r->timeSec == 0.5);
  auto c = p.counters();
  CHECK(c.runsStarted == 2);  // both levels ran, none was cancelled
  CHECK(c.runsCancelled == 0);
  CHECK(c.published == 2);
  CHECK(r->serial == 2);
  // The fine mesh is the one a direct polygonisation gives, and it is closed.
  PolygonizeSettings s;
  s.resolution = 40;
  auto direct = polygonize(compileFieldProgram(makeBlobCreature(), 0.5), s);
  REQUIRE(direct);
  CHECK(r->mesh.triangleCount() == direct->mesh.triangleCount());
  CHECK(analyzeMesh(r->mesh).watertight());
  // The same request again changes nothing.
  CHECK(p.submit(request(creature(), 0.5, 16, 40)) == id);
  REQUIRE(p.waitIdle(60.0));
  CHECK(p.counters().runsStarted == 2);
}

TEST_CASE("preview: with coarse >= fine only the fine level runs", "[poly][preview]") {
  PreviewPolygonizer p(1);
  p.submit(request(creature(), 0.0, 32, 24));
  REQUIRE(p.waitIdle(60.0));
  CHECK(p.counters().runsStarted == 1);
  CHECK(p.latest()->resolution == 24);
  CHECK(p.latest()->final);
}

TEST_CASE("preview: the latest of many quick requests wins", "[poly][preview]") {
  PreviewPolygonizer p(2);
  auto tree = creature();
  uint64_t last = 0;
  for (int i = 0; i <= 20; ++i) last = p.submit(request(tree, i * 0.05, 12, 28));  // scrubbing
  REQUIRE(p.waitIdle(60.0));
  auto r = p.latest();
  REQUIRE(r);
  CHECK(r->requestId == last);
  CHECK(r->timeSec == Approx(1.0));
  CHECK(r->final);
  CHECK(r->resolution == 28);
  // Far fewer runs than requests: superseded requests were skipped or cancelled.
  auto c = p.counters();
  CHECK(c.runsStarted < 2 * 21);
  CHECK(c.published <= c.runsStarted);
}

TEST_CASE("preview: a newer request cancels the run in progress", "[poly][preview]") {
  PreviewPolygonizer p(1);
  // A single heavy level (seconds of work), then a light request once it has started.
  uint64_t heavy = p.submit(request(creature(), 0.0, 600, 600));
  REQUIRE(eventually([&] { return p.counters().runsStarted >= 1; }));
  uint64_t light = p.submit(request(creature(), 1.0, 12, 20));
  CHECK(light == heavy + 1);
  REQUIRE(p.waitIdle(60.0));
  auto c = p.counters();
  CHECK(c.runsCancelled == 1);
  auto r = p.latest();
  REQUIRE(r);
  CHECK(r->requestId == light);  // nothing of the heavy request was published
  CHECK(c.published == 2);       // the light request's two levels
  CHECK(r->resolution == 20);
}

TEST_CASE("preview: a newer request lets the coarse run finish and shows it (scrubbing)", "[poly][preview]") {
  PreviewPolygonizer p(1);
  // A coarse level heavy enough to be caught running (while scrubbing: slower than a frame), then a
  // newer time: the coarse mesh of the older time is still published before the newer request runs.
  uint64_t older = p.submit(request(creature(), 0.0, 220, 240));
  REQUIRE(eventually([&] { return p.counters().runsStarted >= 1; }));
  uint64_t newer = p.submit(request(creature(), 1.0, 12, 20));
  REQUIRE(p.waitIdle(120.0));
  const PreviewCounters c = p.counters();
  CHECK(c.runsCancelled == 0);
  CHECK(c.runsStarted == 3);  // the older request's coarse level, the newer one's two levels
  CHECK(c.published == 3);
  auto r = p.latest();
  REQUIRE(r);
  CHECK(r->requestId == newer);
  CHECK(r->requestId == older + 1);
  CHECK(r->resolution == 20);
  CHECK(r->final);
}

namespace {
// A BlobTree source whose validation takes a while (a tree of thousands of nodes), so that new
// requests come faster than one is validated.
class SlowToValidate final : public PreviewSource {
 public:
  SlowToValidate(std::shared_ptr<const BlobTree> tree, double t) : inner_(blobTreePreviewSource(tree, t)), t_(t) {}
  bool sameAs(const PreviewSource& other) const override {
    auto* o = dynamic_cast<const SlowToValidate*>(&other);
    return o && o->t_ == t_;
  }
  Status validate() const override {
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    return inner_->validate();
  }
  Result<PolygonizeResult> polygonize(int resolution, int threads, const std::atomic<bool>* cancel,
                                      PolygonizeHistory* history) const override {
    return inner_->polygonize(resolution, threads, cancel, history);
  }
  Result<PreviewField> field(int resolution) const override { return inner_->field(resolution); }

 private:
  std::shared_ptr<const PreviewSource> inner_;
  double t_;
};
}  // namespace

TEST_CASE("preview: scrubbing faster than a request is validated still shows coarse answers", "[poly][preview]") {
  PreviewPolygonizer p(1);
  auto tree = creature();
  // A new time every 5 ms for 1.2 s: each request is superseded long before its validation ends.
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(1200);
  int submitted = 0;
  for (double t = 0.0; std::chrono::steady_clock::now() < end; t += 0.01, ++submitted) {
    PreviewRequest r;
    r.source = std::make_shared<const SlowToValidate>(tree, t);
    r.timeSec = t;
    r.coarseResolution = 12;
    r.fineResolution = 24;
    p.submit(std::move(r));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const PreviewCounters during = p.counters();
  INFO(submitted << " requests; " << during.published << " published, " << during.runsCancelled << " cancelled");
  CHECK(during.published >= 3);  // about one per 60 ms validation; none when each request was dropped
  CHECK(during.runsCancelled == 0);
  REQUIRE(p.waitIdle(60.0));
  CHECK(p.latest()->final);
}

TEST_CASE("preview: an invalid tree gives an error naming the node, not a crash", "[poly][preview]") {
  BlobTree bad = makeStarterTree();
  bad.root.children.clear();  // a blend needs at least one child
  PreviewPolygonizer p(1);
  p.submit(request(std::make_shared<const BlobTree>(bad), 0.0, 8, 16));
  REQUIRE(p.waitIdle(30.0));
  auto r = p.latest();
  REQUIRE(r);
  CHECK_THAT(r->error, Catch::Contains("node 1"));
  CHECK(r->mesh.positions.empty());
  CHECK(r->final);
}

TEST_CASE("preview: destroying the worker mid-run returns promptly", "[poly][preview]") {
  auto p = std::make_unique<PreviewPolygonizer>(1);
  p->submit(request(creature(), 0.0, 700, 700));
  REQUIRE(eventually([&] { return p->counters().runsStarted >= 1; }));
  auto t0 = std::chrono::steady_clock::now();
  p.reset();  // cancels and joins
  // Generous bound: only a missing cancel would take the full run (many seconds).
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 30.0);
}
