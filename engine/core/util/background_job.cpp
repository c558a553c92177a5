#include "core/util/background_job.h"

#include <exception>

namespace animorph {

BackgroundJob::BackgroundJob(std::string label, Work work) : label_(std::move(label)) {
  thread_ = std::thread([this, work = std::move(work)] {
    Status s;
    try {
      s = work(progress_);
    } catch (const std::exception& e) {  // a job must not take the editor down: its error is reported
      s = Error{label_ + ": " + e.what()};
    }
    status_ = std::move(s);
    finished_.store(true, std::memory_order_release);
  });
}

BackgroundJob::~BackgroundJob() {
  cancel();
  if (thread_.joinable()) thread_.join();
}

void BackgroundJob::wait() {
  if (thread_.joinable()) thread_.join();
}

bool BackgroundJob::wasCancelled() const { return finished() && isJobCancelled(status_); }

}  // namespace animorph
