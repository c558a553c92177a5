#pragma once
// A fresh temporary directory for a benchmark's files (mkdtemp: a unique name), removed with
// everything in it when the object goes.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace animorph::bench {

class ScratchDir {
 public:
  // prefix: the directory's name before the unique suffix, e.g. "animorph-bench-export".
  explicit ScratchDir(const std::string& prefix) {
    std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(tmpl.data())) path_ = tmpl;
  }
  ~ScratchDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  bool ok() const { return !path_.empty(); }  // false: it could not be created
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace animorph::bench
