#pragma once
// The committed demo morph project the export and playblast benchmarks bake: resources/demo/demo.animorph (or the
// project ANIMORPH_DEMO names), loaded and prepared.
#include <filesystem>
#include <memory>
#include <string>

#include "core/project/project.h"
#include "core/scene/morph_runtime.h"

namespace animorph::bench {

struct DemoMorph {
  std::filesystem::path path;
  Project project;
  std::shared_ptr<const MorphRuntime> runtime;
  std::string error;  // non-empty: could not be loaded or prepared
};

DemoMorph loadDemoMorph();

}  // namespace animorph::bench
