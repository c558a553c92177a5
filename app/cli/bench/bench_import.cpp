// Benchmark: glTF import of a dense skinned character written to a temp dir.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "app/cli/bench/bench.h"
#include "demo/dense.h"
#include "core/io/gltf_export.h"
#include "core/io/gltf_import.h"

namespace {

std::vector<animorph::bench::Row> benchImport(const animorph::bench::Options& opt) {
  namespace fs = std::filesystem;
  const size_t target = opt.quick ? 20000 : 100000;
  const fs::path dir = fs::temp_directory_path() / ("animorph-bench-import-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::create_directories(dir, ec);
  const std::string path = (dir / "dense.glb").string();
  std::vector<animorph::bench::Row> rows;
  const animorph::Character dense = animorph::makeDenseCharacter(target);
  if (auto s = animorph::exportGlb(dense, path); !s) {
    rows.push_back({"export failed: " + s.error(), 0.0, "", "", ""});
    fs::remove_all(dir, ec);
    return rows;
  }
  size_t triangles = 0;
  std::string error;
  const double ms = animorph::bench::medianMs(opt.quick ? 3 : 7, [&] {
    auto c = animorph::importGltf(path);
    if (c) triangles = c->totalTriangles();
    else error = c.error();
  });
  const auto bytes = fs::file_size(path, ec);
  fs::remove_all(dir, ec);
  if (!error.empty()) {
    rows.push_back({"import failed: " + error, 0.0, "", "", ""});
    return rows;
  }
  const std::string size = std::to_string(triangles) + " tris, " + std::to_string(bytes / 1024) + " KiB, skinned";
  rows.push_back({"import skinned .glb", ms, "ms", opt.quick ? "" : "<= 200 ms", size});
  rows.push_back({"triangles imported", static_cast<double>(triangles), "tris", "", ""});
  rows.push_back({"import throughput", triangles / (ms * 1000.0), "Mtri/s", "", ""});
  return rows;
}

}  // namespace

ANIMORPH_BENCH("import", "glTF import of a 100k-triangle skinned character", benchImport);
