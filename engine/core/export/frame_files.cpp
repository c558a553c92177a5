#include "core/export/frame_files.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>

namespace animorph {
namespace fs = std::filesystem;

std::string frameFileName(const std::string& dir, const std::string& name, int frame, const char* ext) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%04d.%s", frame, ext);
  return (fs::path(dir) / (name + buf)).string();
}

std::string resolveOutputPath(const std::string& output, const std::string& baseDir) {
  if (output.empty()) return {};
  std::filesystem::path out(output);
  return (out.is_absolute() ? out : std::filesystem::path(baseDir) / out).lexically_normal().string();
}

std::string framePrefix(const std::string& name) {
  std::string out;
  for (char c : name) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') ? c : '_';
  return out.empty() ? std::string("frame") : out;
}

StagedFiles::~StagedFiles() {
  if (!committed_) discard();
}

std::string StagedFiles::stage(const std::string& finalPath) {
  std::string tmp = finalPath + ".part-" + std::to_string(long(getpid()));
  files_.emplace_back(tmp, finalPath);
  return tmp;
}

Status StagedFiles::commit() {
  // A folder in a file's place would stop its rename half-way through the set: refused first.
  for (const auto& f : files_) {
    std::error_code ec;
    if (fs::is_directory(f.second, ec)) {
      Error e{f.second + ": is a folder, cannot put the finished file there"};
      discard();
      return e;
    }
  }
  for (const auto& [tmp, final] : files_) {
    std::error_code ec;
    fs::rename(tmp, final, ec);
    if (ec) {
      Error e{final + ": cannot rename the finished file into place: " + ec.message()};  // before discard() frees final
      discard();
      return e;
    }
  }
  committed_ = true;
  return Status::success();
}

void StagedFiles::discard() {
  for (const auto& f : files_) {
    std::error_code ec;
    fs::remove(f.first, ec);
  }
  files_.clear();
}

}  // namespace animorph
