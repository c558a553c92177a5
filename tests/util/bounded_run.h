#pragma once
// Runs a piece of work that may misbehave (crash, hang, allocate gigabytes)
// in a forked child with a time limit, and reports how it ended, what it
// returned and how much memory it took.
#include <functional>
#include <string>

namespace animorph::test {

struct BoundedRun {
  bool finished = false;    // returned within the time limit (no crash, no kill)
  int signal = 0;           // the signal that ended the child, if any (SIGALRM: timed out)
  std::string output;       // what fn returned (truncated to 60 KB)
  double seconds = 0.0;     // wall time
  long peakGrowthMiB = 0;   // peak resident memory above the child's size at its start
};

// fn runs in a child process killed after timeoutSec seconds.
BoundedRun runBounded(const std::function<std::string()>& fn, unsigned timeoutSec);

}  // namespace animorph::test
