#pragma once
// A long operation run off the UI thread (opening a project, importing a glTF, exporting a bake):
// the work runs on its own thread, reports its progress and polls a cancel flag through
// JobProgress; the UI thread polls finished() each frame and, once it is, reads status() and
// applies the work's result (kept by the work's closure) to the Document itself. The job never
// touches the Document.
//
// Cancel is cooperative: cancel() sets a flag that the work reads with JobProgress::cancelled()
// between steps and then returns jobCancelled(); a cancelled job's status() is that error.
#include <atomic>
#include <functional>
#include <string>
#include <thread>

#include "core/util/job_progress.h"
#include "core/util/result.h"

namespace animorph {

class BackgroundJob {
 public:
  using Work = std::function<Status(JobProgress&)>;
  // Starts work on a new thread at once. label names the job in the UI ("Export").
  BackgroundJob(std::string label, Work work);
  // Cancels and waits for the work to return.
  ~BackgroundJob();
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  const std::string& label() const { return label_; }
  JobProgress& progress() { return progress_; }
  const JobProgress& progress() const { return progress_; }
  void cancel() { progress_.cancel(); }

  // The work has returned (then status() may be read and the result applied).
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  // Blocks until finished() (tests, shutdown).
  void wait();
  // The work's outcome; only after finished().
  const Status& status() const { return status_; }
  // The work returned jobCancelled().
  bool wasCancelled() const;

 private:
  std::string label_;
  JobProgress progress_;
  Status status_ = Status::success();
  std::atomic<bool> finished_{false};
  std::thread thread_;
};

}  // namespace animorph
