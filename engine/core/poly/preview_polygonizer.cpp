#include "core/poly/preview_polygonizer.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "core/blobtree/compile.h"
#include "core/blobtree/validate.h"
#include "core/util/heap_trim.h"

namespace animorph {

int interactivePreviewThreads() {
  const int hw = int(std::thread::hardware_concurrency());
  return std::max(1, hw - 1);
}

int pacedPreviewThreads() { return std::max(1, int(std::thread::hardware_concurrency())); }

namespace {
bool sameRequest(const PreviewRequest& a, const PreviewRequest& b) {
  if (a.timeSec != b.timeSec || a.coarseResolution != b.coarseResolution || a.fineResolution != b.fineResolution)
    return false;
  if (a.source || b.source) return a.source && b.source && a.source->sameAs(*b.source);
  if (a.tree == b.tree) return true;
  return a.tree && b.tree && *a.tree == *b.tree;
}

class BlobTreeSource final : public PreviewSource {
 public:
  BlobTreeSource(std::shared_ptr<const BlobTree> tree, double timeSec) : tree_(std::move(tree)), timeSec_(timeSec) {}
  bool sameAs(const PreviewSource& other) const override {
    auto* o = dynamic_cast<const BlobTreeSource*>(&other);
    return o && o->timeSec_ == timeSec_ && (o->tree_ == tree_ || *o->tree_ == *tree_);
  }
  Status validate() const override { return validateBlobTree(*tree_); }
  Result<PolygonizeResult> polygonize(int resolution, int threads, const std::atomic<bool>* cancel,
                                      PolygonizeHistory* history) const override {
    std::call_once(compiled_, [&] { program_ = compileFieldProgram(*tree_, timeSec_); });
    return polygonizePreviewProgram(program_, resolution, threads, cancel, history);
  }
  Result<PreviewField> field(int) const override {
    if (Status s = validateBlobTree(*tree_); !s) return Error{s.error()};
    return PreviewField{compileFieldProgram(*tree_, timeSec_), std::nullopt, 0.0f, 1.0f, nullptr, std::nullopt, nullptr};
  }

 private:
  std::shared_ptr<const BlobTree> tree_;
  double timeSec_;
  mutable std::once_flag compiled_;  // the worker compiles once for both levels
  mutable FieldProgram program_;
};
}  // namespace

Result<PolygonizeResult> polygonizePreviewProgram(const FieldProgram& program, int resolution, int threads,
                                                  const std::atomic<bool>* cancel, PolygonizeHistory* history) {
  PolygonizeSettings settings;
  settings.resolution = resolution;
  settings.threads = threads;
  settings.cancel = cancel;
  settings.colors = true;
  if (history) {
    // Stay on the last frame's grid while the shape fits in it, so its blocks can be reused.
    auto own = polygonizeGrid(program, settings);
    if (!own) return Error{own.error()};
    if (!own->empty) settings.grid = scrubbingGrid(*own, *history);
    settings.history = history;
    settings.reuseToleranceCells = kPreviewReuseToleranceCells;
  }
  return animorph::polygonize(program, settings);
}

std::shared_ptr<const PreviewSource> blobTreePreviewSource(std::shared_ptr<const BlobTree> tree, double timeSec) {
  return std::make_shared<const BlobTreeSource>(std::move(tree), timeSec);
}

PreviewPolygonizer::PreviewPolygonizer(int threads) : threads_(threads), worker_([this] { run(); }) {}

PreviewPolygonizer::~PreviewPolygonizer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    cancel_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

uint64_t PreviewPolygonizer::submit(PreviewRequest request) {
  if (!request.tree && !request.source) return 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pendingId_ != 0 && sameRequest(request, pending_)) return pendingId_;
    pending_ = std::move(request);
    ++pendingId_;
    // The run in progress (if any) answers an older request: a fine one stops, a coarse one is
    // finished and shown (the loop below then takes this request).
    if (runningLevel_ != 0) cancel_ = true;
  }
  wake_.notify_all();
  return pendingId_;
}

std::shared_ptr<const PreviewResult> PreviewPolygonizer::latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_;
}

bool PreviewPolygonizer::busy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return running_ || doneId_ != pendingId_;
}

bool PreviewPolygonizer::waitIdle(double timeoutSec) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return idle_.wait_for(lock, std::chrono::duration<double>(timeoutSec),
                        [&] { return !running_ && doneId_ == pendingId_; });
}

PreviewCounters PreviewPolygonizer::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

namespace {
std::atomic<void (*)()> g_publishHook{nullptr};
std::mutex g_publishedMutex;
std::condition_variable g_publishedCv;
uint64_t g_published = 0;  // under g_publishedMutex
}  // namespace

void PreviewPolygonizer::setPublishHook(void (*hook)()) { g_publishHook = hook; }

uint64_t PreviewPolygonizer::publishedTotal() {
  std::lock_guard<std::mutex> lock(g_publishedMutex);
  return g_published;
}

bool PreviewPolygonizer::waitForPublish(uint64_t seen, double timeoutSec) {
  std::unique_lock<std::mutex> lock(g_publishedMutex);
  return g_publishedCv.wait_for(lock, std::chrono::duration<double>(std::max(0.0, timeoutSec)),
                                [&] { return g_published != seen; });
}

void PreviewPolygonizer::publish(std::shared_ptr<PreviewResult> r) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    r->serial = serial_.load() + 1;
    latest_ = std::move(r);
    serial_ = latest_->serial;
    ++counters_.published;
  }
  {
    std::lock_guard<std::mutex> lock(g_publishedMutex);
    ++g_published;
  }
  g_publishedCv.notify_all();
  if (auto hook = g_publishHook.load()) hook();
}

void PreviewPolygonizer::run() {
  for (;;) {
    PreviewRequest req;
    uint64_t id = 0;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || pendingId_ != doneId_; });
      if (stop_) return;
      req = pending_;
      id = pendingId_;
      running_ = true;
      cancel_ = false;  // a submit after this point sets it again (or not: runningLevel_)
      // From now on the request's first level is under way, its validation included: a newer
      // request must not cancel a coarse answer before it has started.
      runningLevel_ = req.coarseResolution >= req.fineResolution ? 1 : 0;
    }
    auto newer = [&] {
      std::lock_guard<std::mutex> lock(mutex_);
      return stop_ || pendingId_ != id;
    };
    auto stopping = [&] {
      std::lock_guard<std::mutex> lock(mutex_);
      return stop_;
    };

    auto fail = [&](std::string message) {
      auto r = std::make_shared<PreviewResult>();
      r->requestId = id;
      r->timeSec = req.timeSec;
      r->final = true;
      r->error = std::move(message);
      publish(std::move(r));
    };
    std::shared_ptr<const PreviewSource> source = req.source ? req.source : blobTreePreviewSource(req.tree, req.timeSec);
    if (Status s = source->validate(); !s) {
      fail(s.error());
    } else {
      int levels[2] = {req.coarseResolution, req.fineResolution};
      int first = req.coarseResolution >= req.fineResolution ? 1 : 0;
      for (int level = first; level < 2; ++level) {
        // A newer request skips the refinement, not the coarse answer: while scrubbing, requests
        // come faster than one is validated and polygonised, and breaking here would show none.
        if (level == 1 ? newer() : stopping()) break;
        const int resolution = std::clamp(levels[level], 2, 4096);
        {
          std::lock_guard<std::mutex> lock(mutex_);
          ++counters_.runsStarted;
          runningLevel_ = level;
        }
        auto result = source->polygonize(resolution, req.threads > 0 ? req.threads : threads_, &cancel_, &history_[level]);
        {
          std::lock_guard<std::mutex> lock(mutex_);
          runningLevel_ = -1;
        }
        if (!result) {
          fail(result.error());
          break;
        }
        if (result->cancelled) {
          std::lock_guard<std::mutex> lock(mutex_);
          ++counters_.runsCancelled;
          break;
        }
        auto r = std::make_shared<PreviewResult>();
        r->requestId = id;
        r->timeSec = req.timeSec;
        r->resolution = resolution;
        r->final = level == 1;
        r->mesh = std::move(result->mesh);
        r->stats = result->stats;
        publish(std::move(r));
      }
    }
    // The request is answered and no newer one waits: give the run's freed working memory (grids,
    // cell tables: tens of MiB at 128^3, in this thread's malloc arena) back to the system, or the
    // editor's resident memory keeps it for every preview worker that ever ran (util/heap_trim.h).
    if (!newer()) trimFreedHeap();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      running_ = false;
      runningLevel_ = -1;
      // Only a request answered without a newer one arriving is done; otherwise loop.
      if (pendingId_ == id) doneId_ = id;
    }
    idle_.notify_all();
  }
}

}  // namespace animorph
