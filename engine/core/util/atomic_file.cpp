#include "core/util/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <tuple>
#include <utility>

namespace animorph {
namespace {

Error sysError(const std::string& path, const char* what) {
  return Error{path + ": " + what + ": " + std::strerror(errno)};
}

namespace fs = std::filesystem;

constexpr int kNameAttempts = 64;

// ".NAME.tmp": the start of every temporary name of this target; a random
// suffix of letters and digits follows.
std::string tempPrefix(const std::string& path) { return "." + fs::path(path).filename().string() + ".tmp"; }

std::string randomSuffix() {
  static thread_local std::mt19937_64 rng = [] {
    std::random_device rd;
    std::seed_seq seq{rd(), rd(), rd(), rd(), static_cast<unsigned>(::getpid())};
    return std::mt19937_64(seq);
  }();
  static const char kDigits[] = "0123456789abcdef";
  std::string s;
  for (uint64_t v = rng(), i = 0; i < 16; ++i, v >>= 4) s += kDigits[v & 15];
  return s;
}

// Whether `name` still names the file open as fd.
bool sameFile(int fd, const fs::path& name) {
  struct stat a {}, b {};
  return ::fstat(fd, &a) == 0 && ::stat(name.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

Status writeAndSync(int fd, std::string_view contents, const std::string& path) {
  const char* data = contents.data();
  size_t left = contents.size();
  while (left > 0) {
    ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return sysError(path, "write failed");
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) return sysError(path, "fsync failed");
  return Status::success();
}

// Links the unnamed (O_TMPFILE) file fd into dir under a fresh name;
// nullopt when linking is impossible here.
std::optional<fs::path> linkUnique(int fd, const fs::path& dir, const std::string& prefix) {
  const std::string self = "/proc/self/fd/" + std::to_string(fd);
  for (int i = 0; i < kNameAttempts; ++i) {
    fs::path name = dir / (prefix + randomSuffix());
    if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return name;
    if (errno != EEXIST) return std::nullopt;
  }
  return std::nullopt;
}

// Creates and locks a new file with a fresh name in dir (O_EXCL: never an
// existing one), retrying when a name is taken.
Result<std::pair<int, fs::path>> createUnique(const fs::path& dir, const std::string& prefix, const std::string& path) {
  for (int i = 0; i < kNameAttempts; ++i) {
    fs::path name = dir / (prefix + randomSuffix());
    int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
      if (errno == EEXIST) continue;
      return sysError(path, "cannot create temporary file");
    }
    // Between open and flock another save's clean-up may take the file for a
    // stale one and remove it: then start again under another name.
    if (::flock(fd, LOCK_EX) == 0 && sameFile(fd, name)) return std::pair{fd, name};
    ::close(fd);
  }
  return Error{path + ": cannot create temporary file: no free name after " + std::to_string(kNameAttempts) +
               " attempts"};
}

const char* fileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

}  // namespace

Status writeFileAtomic(const std::string& path, std::string_view contents) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = tempPrefix(path);
  fs::path name;
  int fd = -1;
  // Preferred: an unnamed O_TMPFILE, written and synced, then given a unique
  // name only for the moment before the rename.
  int anon = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  if (anon >= 0) {
    ::flock(anon, LOCK_EX);
    if (Status s = writeAndSync(anon, contents, path); !s) {
      ::close(anon);
      return s;
    }
    if (auto linked = linkUnique(anon, dir, prefix)) {
      fd = anon;
      name = *linked;
    } else {
      ::close(anon);  // no /proc or no linkat here: fall back to a named file
    }
  }
  if (fd < 0) {
    auto created = createUnique(dir, prefix, path);
    if (!created) return Error{created.error()};
    std::tie(fd, name) = *created;
    if (Status s = writeAndSync(fd, contents, path); !s) {
      ::unlink(name.c_str());
      ::close(fd);
      return s;
    }
  }
  if (::rename(name.c_str(), target.c_str()) != 0) {
    Error e = sysError(path, "rename failed");
    ::unlink(name.c_str());
    ::close(fd);
    return e;
  }
  ::close(fd);
  int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  removeStaleTemporaries(path);
  return Status::success();
}

int removeStaleTemporaries(const std::string& path) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = tempPrefix(path);
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) continue;
    if (!std::all_of(entry.begin() + static_cast<long>(prefix.size()), entry.end(),
                     [](unsigned char ch) { return std::isalnum(ch) != 0; }))
      continue;
    int fd = ::open(it->path().c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    struct stat st {};
    // A save in progress holds the lock; one that was killed released it.
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && ::flock(fd, LOCK_EX | LOCK_NB) == 0 &&
        sameFile(fd, it->path()) && ::unlink(it->path().c_str()) == 0)
      ++removed;
    ::close(fd);
  }
  return removed;
}

Result<std::string> readFile(const std::string& path, size_t maxBytes, JobProgress* progress) {
  // O_NONBLOCK: opening a FIFO for reading must not wait for a writer.
  int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return sysError(path, "cannot open");
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    Error e = sysError(path, "cannot stat");
    ::close(fd);
    return e;
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return Error{path + ": is " + fileKind(st.st_mode) + ", not a regular file"};
  }
  if (static_cast<unsigned long long>(st.st_size) > maxBytes) {
    ::close(fd);
    return Error{path + ": is " + std::to_string(st.st_size) + " bytes, more than the " + std::to_string(maxBytes) +
                 " bytes allowed"};
  }
  // A regular file never blocks; reads stop at maxBytes + 1 even if the file
  // grows meanwhile.
  std::string out;
  out.resize(static_cast<size_t>(st.st_size));
  size_t have = 0;
  const size_t piece = progress ? size_t(1) << 20 : SIZE_MAX;
  const double doneBefore = progress ? progress->done() : 0.0;
  if (progress) progress->addTotal(double(st.st_size));
  for (;;) {
    if (progress) {
      progress->setDone(doneBefore + double(std::min(have, size_t(st.st_size))));
      if (progress->cancelled()) {
        ::close(fd);
        return jobCancelled();
      }
    }
    if (have == out.size()) {
      if (out.size() > maxBytes) break;
      out.resize(std::min(maxBytes + 1, std::max<size_t>(out.size() * 2, 4096)));
    }
    ssize_t n = ::read(fd, out.data() + have, std::min(piece, out.size() - have));
    if (n < 0) {
      if (errno == EINTR) continue;
      Error e = sysError(path, "read failed");
      ::close(fd);
      return e;
    }
    if (n == 0) break;
    have += static_cast<size_t>(n);
  }
  ::close(fd);
  if (have > maxBytes)
    return Error{path + ": grew past the " + std::to_string(maxBytes) + " bytes allowed while being read"};
  out.resize(have);
  return out;
}

}  // namespace animorph
