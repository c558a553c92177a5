#include "app/cli/bench/bench_demo_project.h"

#include <cstdlib>

#include "core/project/asset_cache.h"
#include "core/project/project_io.h"

namespace animorph::bench {

DemoMorph loadDemoMorph() {
  DemoMorph d;
  const char* demoEnv = std::getenv("ANIMORPH_DEMO");
  d.path = demoEnv ? std::filesystem::path(demoEnv)
                   : std::filesystem::path(ANIMORPH_SOURCE_DIR) / "resources/demo/demo.animorph";
  auto project = loadProject(d.path.string());
  if (!project) {
    d.error = project.error();
    return d;
  }
  d.project = std::move(*project);
  AssetCache assets;
  auto rt = prepareMorph(d.project, d.path.parent_path().string(), assets);
  if (!rt) d.error = rt.error();
  else d.runtime = *rt;
  return d;
}

}  // namespace animorph::bench
