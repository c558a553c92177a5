#pragma once
// The demo creature -> gear morph for benchmarks: both characters written to a
// fresh temporary directory and a project made as `animorph-cli new` makes it
// (target aligned when their sizes differ by more than 4x). The directory is
// removed with the object.
#include <optional>
#include <string>

#include "app/cli/bench/bench_scratch_dir.h"
#include "core/project/project.h"

namespace animorph::bench {

struct DemoMorphDir {
  ScratchDir scratch{"animorph-bench"};
  std::string dir;                // empty: the directory could not be made
  std::optional<Project> project; // empty: the project could not be made
  DemoMorphDir();
  DemoMorphDir(const DemoMorphDir&) = delete;
  DemoMorphDir& operator=(const DemoMorphDir&) = delete;
};

}  // namespace animorph::bench
