#include "poly/preview_polygonizer.h"

#include <algorithm>
#include <chrono>

#include "blobtree/compile.h"
#include "blobtree/validate.h"

namespace animorph {

namespace {
bool sameRequest(const PreviewRequest& a, const PreviewRequest& b) {
  if (a.timeSec != b.timeSec || a.coarseResolution != b.coarseResolution || a.fineResolution != b.fineResolution)
    return false;
  if (a.tree == b.tree) return true;
  return a.tree && b.tree && *a.tree == *b.tree;
}
}  // namespace

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
  if (!request.tree) return 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pendingId_ != 0 && sameRequest(request, pending_)) return pendingId_;
    pending_ = std::move(request);
    ++pendingId_;
    cancel_ = true;  // the run in progress (if any) answers an older request
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

void PreviewPolygonizer::publish(std::shared_ptr<PreviewResult> r) {
  std::lock_guard<std::mutex> lock(mutex_);
  r->serial = serial_.load() + 1;
  latest_ = std::move(r);
  serial_ = latest_->serial;
  ++counters_.published;
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
      cancel_ = false;  // a submit after this point sets it again
    }
    auto newer = [&] {
      std::lock_guard<std::mutex> lock(mutex_);
      return stop_ || pendingId_ != id;
    };

    auto fail = [&](std::string message) {
      auto r = std::make_shared<PreviewResult>();
      r->requestId = id;
      r->timeSec = req.timeSec;
      r->final = true;
      r->error = std::move(message);
      publish(std::move(r));
    };
    if (Status s = validateBlobTree(*req.tree); !s) {
      fail(s.error());
    } else {
      FieldProgram program = compileFieldProgram(*req.tree, req.timeSec);
      int levels[2] = {req.coarseResolution, req.fineResolution};
      int first = req.coarseResolution >= req.fineResolution ? 1 : 0;
      for (int level = first; level < 2; ++level) {
        if (newer()) break;
        PolygonizeSettings settings;
        settings.resolution = std::clamp(levels[level], 2, 4096);
        settings.threads = threads_;
        settings.cancel = &cancel_;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          ++counters_.runsStarted;
        }
        auto result = polygonize(program, settings);
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
        r->resolution = settings.resolution;
        r->final = level == 1;
        r->mesh = std::move(result->mesh);
        r->stats = result->stats;
        publish(std::move(r));
      }
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      running_ = false;
      // Only a request answered without a newer one arriving is done; otherwise loop.
      if (pendingId_ == id) doneId_ = id;
    }
    idle_.notify_all();
  }
}

}  // namespace animorph
