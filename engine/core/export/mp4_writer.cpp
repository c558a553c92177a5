#include "core/export/mp4_writer.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <pthread.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

extern char** environ;

namespace animorph {
namespace fs = std::filesystem;

namespace {
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf";

// A label as drawtext text: only characters that need no escaping in a filter graph are kept.
std::string drawtextSafe(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == ' ' || c == '-' ? c : '_';
  return out;
}

// write() of all bytes to a pipe; a reader that went away is EPIPE here, not a SIGPIPE that would
// end the program (the signal is blocked on this thread and a pending one taken back).
bool writeAll(int fd, const uint8_t* data, size_t size) {
  sigset_t pipeSet, old;
  sigemptyset(&pipeSet);
  sigaddset(&pipeSet, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipeSet, &old);
  bool ok = true;
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ok = false;
      break;
    }
    data += n;
    size -= size_t(n);
  }
  if (!ok && errno == EPIPE) {
    const timespec zero{0, 0};
    sigtimedwait(&pipeSet, nullptr, &zero);
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return ok;
}
}  // namespace

std::string mp4BurnInFilter(const Mp4Options& o) {
  if (!o.burnIn) return {};
  const std::string style = std::string("drawtext=fontfile=") + kFont + ":fontsize=" +
                            std::to_string(std::max(12u, o.height / 24)) +
                            ":fontcolor=white:box=1:boxcolor=black@0.5:boxborderw=6:x=12:y=12:text='frame %{eif\\:n+" +
                            std::to_string(o.firstFrame) + "\\:d\\:4}";
  if (o.stages.empty()) return style + "'";
  std::string filter;
  for (const FrameStageSpan& s : o.stages) {
    if (!filter.empty()) filter += ",";
    // n counts from 0 at the first frame.
    filter += style + "   " + drawtextSafe(s.label) + "':enable='between(n\\," + std::to_string(s.first - o.firstFrame) +
              "\\," + std::to_string(s.last - o.firstFrame) + ")'";
  }
  return filter;
}

Result<std::unique_ptr<Mp4Writer>> Mp4Writer::start(const Mp4Options& o) {
  if (o.width < 16 || o.height < 16 || o.width % 2 || o.height % 2)
    return Error{o.path + ": the picture size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                 " is not even numbers of 16 or more (H.264 needs even sizes)"};
  std::error_code ec;
  if (o.burnIn && !fs::exists(kFont, ec))
    return Error{o.path + ": the burn-in needs the font " + std::string(kFont) + " (Debian package fonts-dejavu-core)"};
  std::unique_ptr<Mp4Writer> w(new Mp4Writer());
  w->o_ = o;
  w->tmp_ = o.path + ".part-" + std::to_string(long(getpid()));
  w->log_ = w->tmp_ + ".log";
  char rate[32], size[32];
  std::snprintf(rate, sizeof rate, "%g", o.fps > 0.0 ? o.fps : 24.0);
  std::snprintf(size, sizeof size, "%ux%u", o.width, o.height);
  std::vector<std::string> args = {"ffmpeg", "-hide_banner", "-nostdin", "-loglevel", "error", "-y", "-f", "rawvideo",
                                   "-pix_fmt", "rgba", "-s", size, "-r", rate, "-i", "pipe:0"};
  if (o.burnIn) args.insert(args.end(), {"-vf", mp4BurnInFilter(o)});
  args.insert(args.end(), {"-c:v", "libx264", "-preset", "veryfast", "-pix_fmt", "yuv420p", "-movflags", "+faststart",
                           "-f", "mp4", w->tmp_});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return Error{o.path + ": cannot make a pipe to ffmpeg: " + std::strerror(errno)};
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, w->log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int rc = posix_spawnp(&w->pid_, "ffmpeg", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(fds[0]);
  if (rc != 0) {
    ::close(fds[1]);
    w->pid_ = -1;
    fs::remove(w->log_, ec);
    return Error{o.path + ": cannot start ffmpeg (Debian package ffmpeg): " + std::strerror(rc)};
  }
  w->fd_ = fds[1];
  return w;
}

Mp4Writer::~Mp4Writer() {
  if (!finished_) stop();
}

std::string Mp4Writer::ffmpegSaid() const {
  std::ifstream f(log_);
  std::string line, last;
  while (std::getline(f, line))
    if (!line.empty()) last = line;
  return last.empty() ? std::string() : ": " + last;
}

void Mp4Writer::stop() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  pid_ = -1;
  std::error_code ec;
  fs::remove(tmp_, ec);
  fs::remove(log_, ec);
}

Status Mp4Writer::addFrame(const std::vector<uint8_t>& rgba) {
  const size_t want = size_t(o_.width) * o_.height * 4;
  if (rgba.size() != want)
    return Error{o_.path + ": frame " + std::to_string(frames_) + " has " + std::to_string(rgba.size()) +
                 " bytes, expected " + std::to_string(want)};
  if (fd_ < 0) return Error{o_.path + ": ffmpeg's input is closed"};
  if (!writeAll(fd_, rgba.data(), rgba.size())) {
    const std::string said = ffmpegSaid();
    stop();
    return Error{o_.path + ": ffmpeg stopped taking frames" + said};
  }
  ++frames_;
  return {};
}

Status Mp4Writer::finish() {
  if (pid_ <= 0) return Error{o_.path + ": ffmpeg is not running (an earlier frame failed)"};
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  int status = 0;
  while (pid_ > 0 && waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string said = ffmpegSaid();
    stop();
    return Error{o_.path + ": ffmpeg failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")" + said};
  }
  std::error_code ec;
  fs::rename(tmp_, o_.path, ec);
  if (ec) {
    stop();
    return Error{o_.path + ": cannot rename the finished file into place: " + ec.message()};
  }
  fs::remove(log_, ec);
  finished_ = true;
  return {};
}

}  // namespace animorph
