#include "core/util/job_progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace animorph {

namespace {
constexpr const char* kCancelled = "cancelled";
}

Error jobCancelled() { return Error{kCancelled}; }
bool isJobCancelled(const Status& s) { return !s.ok() && s.error() == kCancelled; }

void JobProgress::advance(double steps) {
  double d = done_.load();
  while (!done_.compare_exchange_weak(d, d + steps)) {
  }
}

void JobProgress::addTotal(double steps) {
  double t = total_.load();
  while (!total_.compare_exchange_weak(t, t + steps)) {
  }
}

void JobProgress::setStage(std::string stage) {
  std::lock_guard<std::mutex> lock(stageMutex_);
  stage_ = std::move(stage);
}

std::string JobProgress::stage() const {
  std::lock_guard<std::mutex> lock(stageMutex_);
  return stage_;
}

double JobProgress::fraction() const {
  const double t = total_.load(), d = done_.load();
  if (!(t > 0.0)) return 0.0;
  return std::clamp(d / t, 0.0, 1.0);
}

double JobProgress::elapsedSec() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double JobProgress::secondsLeft() const {
  const double f = fraction();
  if (f <= 0.0) return -1.0;
  return elapsedSec() * (1.0 - f) / f;
}

std::string formatTimeLeft(double seconds) {
  if (seconds < 0.0 || !std::isfinite(seconds)) return {};
  const long s = std::lround(std::ceil(seconds));
  char buf[48];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s / 60) % 60);
  else if (s >= 60) std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ld s", s);
  return buf;
}

}  // namespace animorph
