#pragma once
// What a long operation reports while it runs (done of total steps, the stage, the time left) and
// the cancel flag it polls; shared by the worker and the UI thread (BackgroundJob runs the work).
// A function that takes a JobProgress* accepts null for "no progress, no cancel".
#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

#include "core/util/result.h"

namespace animorph {

// The error a cancelled job returns (and what BackgroundJob::wasCancelled() recognises).
Error jobCancelled();
// s is the error jobCancelled() made.
bool isJobCancelled(const Status& s);

// What the work reports and what the UI reads, from either thread.
class JobProgress {
 public:
  // Progress: done of total steps (frames, bytes); the time left is estimated from it.
  void setTotal(double total) { total_.store(total); }
  void setDone(double done) { done_.store(done); }
  void addTotal(double steps);
  double done() const { return done_.load(); }
  double total() const { return total_.load(); }
  void advance(double steps = 1.0);
  // What the work is doing now ("reading", "frame 12 of 145").
  void setStage(std::string stage);
  std::string stage() const;

  // 0..1; 0 while the total is not known.
  double fraction() const;
  double elapsedSec() const;
  // Seconds left at the rate so far; negative while no estimate can be made (nothing done yet).
  double secondsLeft() const;

  void cancel() { cancel_.store(true); }
  bool cancelled() const { return cancel_.load(); }
  // For work that polls a flag itself (PolygonizeSettings::cancel, MorphFrameSettings::cancel).
  const std::atomic<bool>* cancelFlag() const { return &cancel_; }

 private:
  std::atomic<double> total_{0.0}, done_{0.0};
  std::atomic<bool> cancel_{false};
  mutable std::mutex stageMutex_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// "1 min 05 s", "12 s", "" for a negative estimate.
std::string formatTimeLeft(double seconds);

}  // namespace animorph
