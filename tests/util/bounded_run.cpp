#include "util/bounded_run.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <stdexcept>

namespace animorph::test {
namespace {

// Resident set size of this process in KiB (from /proc/self/statm).
long residentKiB() {
  long pages = 0, resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * (::sysconf(_SC_PAGESIZE) / 1024);
}

void writeAll(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

}  // namespace

BoundedRun runBounded(const std::function<std::string()>& fn, unsigned timeoutSec) {
  int out[2], start[2];
  if (::pipe(out) != 0 || ::pipe(start) != 0) throw std::runtime_error("pipe failed");
  const auto t0 = std::chrono::steady_clock::now();
  std::fflush(nullptr);
  pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::close(out[0]);
    ::close(start[0]);
    ::signal(SIGALRM, SIG_DFL);
    ::alarm(timeoutSec);
    writeAll(start[1], std::to_string(residentKiB()));
    ::close(start[1]);
    std::string result = fn();
    if (result.size() > 60000) result.resize(60000);
    writeAll(out[1], result);
    ::_exit(0);
  }
  ::close(out[1]);
  ::close(start[1]);
  auto drain = [](int fd) {
    std::string s;
    char buf[4096];
    for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) s.append(buf, static_cast<size_t>(n));
    ::close(fd);
    return s;
  };
  const std::string startKiB = drain(start[0]);
  BoundedRun r;
  r.output = drain(out[0]);
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.finished = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  const long base = startKiB.empty() ? 0 : std::stol(startKiB);
  r.peakGrowthMiB = (usage.ru_maxrss - base) / 1024;
  return r;
}

}  // namespace animorph::test
