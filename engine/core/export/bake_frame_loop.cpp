#include "core/export/bake_frame_loop.h"

#include <algorithm>
#include <atomic>
#include <string>
#include <thread>
#include <vector>

namespace animorph {

Status runFrameLoop(int first, int count, int jobs, JobProgress& progress, const std::function<Status(int k)>& bakeOne,
                    const std::function<void(int frame)>& frameDone) {
  std::vector<Status> results(size_t(std::max(count, 0)));
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  auto worker = [&] {
    while (!failed.load() && !progress.cancelled()) {
      const int k = next.fetch_add(1);
      if (k >= count) return;
      const int f = first + k;
      progress.setStage("baking frame " + std::to_string(f) + " (" + std::to_string(k + 1) + " of " +
                        std::to_string(count) + ")");
      results[size_t(k)] = bakeOne(k);
      if (!results[size_t(k)]) {
        failed.store(true);
        return;
      }
      progress.advance();
      if (frameDone) frameDone(f);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < std::min(jobs, count); ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  // Frames are taken in order, so every frame below a failing one was baked: the lowest failing
  // frame is the one a sequential loop would have stopped at.
  for (int k = 0; k < count; ++k) {
    const Status& r = results[size_t(k)];
    if (r) continue;
    if (isJobCancelled(r)) return jobCancelled();
    return Error{"frame " + std::to_string(first + k) + ": " + r.error()};
  }
  if (progress.cancelled()) return jobCancelled();
  return Status::success();
}

}  // namespace animorph
