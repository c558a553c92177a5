#pragma once
// A progress line for animorph-cli's long commands.
#include <unistd.h>

#include <cstdio>
#include <mutex>

namespace animorph::cli {

// One progress line on a terminal, redrawn in place; nothing when stdout is not a tty.
class ProgressBar {
 public:
  ProgressBar(const char* what, int total) : what_(what), total_(total), tty_(isatty(fileno(stdout)) != 0) {}
  void step() {
    std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    if (!tty_) return;
    const int width = 30, fill = total_ > 0 ? done_ * width / total_ : width;
    std::printf("\r%s [%.*s%.*s] %d/%d", what_, fill, "##############################", width - fill,
                "..............................", done_, total_);
    if (done_ == total_) std::printf("\n");
    std::fflush(stdout);
  }

 private:
  const char* what_;
  int total_;
  bool tty_;
  int done_ = 0;
  std::mutex mutex_;
};

}  // namespace animorph::cli
