// Benchmark of exporting the demo morph: every frame of the 145-frame demo
// baked at 64^3 and written as one animated glTF, with the same frames written
// as a PLY sequence as the baseline in the same run; and its implicit (B->C)
// frames as OpenVDB level sets, against baking and writing them as PLY.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/export/frame_volume.h"
#include "app/cli/bench/bench.h"
#include "app/cli/bench/bench_demo_project.h"
#include "app/cli/bench/bench_scratch_dir.h"
#include "core/project/project_io.h"
#include "core/io/gltf_sequence_export.h"
#include "core/io/vdb_export.h"
#include "core/scene/morph_runtime.h"
#include "core/io/mesh_io.h"

namespace {

using namespace animorph;
using animorph::bench::Row;
namespace fs = std::filesystem;

double sinceMs(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Row> benchExport(const bench::Options& opt) {
  std::vector<Row> rows;
  const bench::DemoMorph dm = bench::loadDemoMorph();
  if (!dm.error.empty()) return {{"skipped", 0, "", "", dm.error}};
  const Project* project = &dm.project;
  const auto* rt = &dm.runtime;
  const bench::ScratchDir scratch("animorph-bench-export");
  if (!scratch.ok()) return {{"skipped", 0, "", "", "cannot create a temporary directory"}};
  const fs::path& dir = scratch.path();

  const int first = project->timeline.frameStart;
  const int last = opt.quick ? first + 24 : project->timeline.frameEnd;
  const int res = opt.quick ? 32 : 64;
  const int count = last - first + 1;
  // Bake: the frames in order, each polygonised on all threads.
  auto t0 = std::chrono::steady_clock::now();
  std::vector<TriangleMesh> meshes;
  std::vector<double> frameBakeMs;
  for (int f = first; f <= last; ++f) {
    const auto f0 = std::chrono::steady_clock::now();
    MorphFrameSettings s;
    s.resolution = res;
    auto fr = evaluateMorphFrame(**rt, project->timeline.frameToSec(f), s);
    if (!fr) return {{"skipped", 0, "", "", "frame " + std::to_string(f) + ": " + fr.error()}};
    meshes.push_back(std::move(fr->mesh));
    frameBakeMs.push_back(sinceMs(f0));
  }
  const double bakeMs = sinceMs(t0);

  // The glTF: frames added, then the file written atomically.
  t0 = std::chrono::steady_clock::now();
  GltfSequenceOptions so;
  so.name = project->name;
  so.fps = project->timeline.fps;
  so.firstFrame = first;
  GltfSequenceWriter writer(so);
  Status st;
  for (size_t k = 0; k < meshes.size() && st; ++k) st = writer.addFrame(meshes[k]);
  const int distinct = writer.meshCount();
  const std::string glb = (dir / "demo.glb").string();
  if (st) st = writeGltfSequence(writer, glb);
  const double gltfMs = sinceMs(t0);
  std::error_code ec;
  const double mb = double(fs::file_size(glb, ec)) / 1e6;

  // Baseline: the same frames as a PLY sequence.
  t0 = std::chrono::steady_clock::now();
  double plyBytes = 0.0;
  std::vector<double> framePlyMs;
  for (int k = 0; k < count; ++k) {
    const auto f0 = std::chrono::steady_clock::now();
    char name[32];
    std::snprintf(name, sizeof name, "demo_%04d.ply", first + k);
    if (Status p = writePly(meshes[size_t(k)], (dir / name).string()); !p) st = p;
    plyBytes += double(fs::file_size(dir / name, ec));
    framePlyMs.push_back(sinceMs(f0));
  }
  const double plyMs = sinceMs(t0);
  if (!st) return {{"skipped", 0, "", "", st.error()}};

  char note[200];
  std::snprintf(note, sizeof note, "%d frames at %d^3: bake %.2f s + glTF %.0f ms (%d meshes, %.1f MB)", count, res,
                bakeMs / 1000.0, gltfMs, distinct, mb);
  rows.push_back({"demo -> glTF (bake + write)", (bakeMs + gltfMs) / 1000.0, "s", "<= 5 s at 64^3", note});
  std::snprintf(note, sizeof note, "baseline: the same frames as %d PLY files %.0f ms (%.1f MB): %.2fx", count, plyMs,
                plyBytes / 1e6, gltfMs / plyMs);
  rows.push_back({"write the glTF", gltfMs, "ms", "", note});

  // The implicit frames as VDB level sets (sampled from the field, then written); baseline: the
  // same frames baked (polygonised) and written as PLY above.
  double sampleMs = 0.0, vdbWriteMs = 0.0, vdbBytes = 0.0, meshMs = 0.0;
  int volumes = 0;
  size_t voxels = 0;
  for (int k = 0; k < count && st; ++k) {
    t0 = std::chrono::steady_clock::now();
    auto band = morphFrameLevelSet(**rt, project->timeline.frameToSec(first + k), res, 0, nullptr);
    if (!band) return {{"skipped", 0, "", "", "frame " + std::to_string(first + k) + ": " + band.error()}};
    if (!*band) continue;  // a skinned-mesh frame: no field
    sampleMs += sinceMs(t0);
    t0 = std::chrono::steady_clock::now();
    const fs::path vdb = dir / ("demo_" + std::to_string(first + k) + ".vdb");
    st = writeVdbLevelSet(**band, vdb.string());
    vdbWriteMs += sinceMs(t0);
    vdbBytes += double(fs::file_size(vdb, ec));
    voxels += (*band)->index.size();
    meshMs += frameBakeMs[size_t(k)] + framePlyMs[size_t(k)];
    ++volumes;
  }
  if (!st) return {{"skipped", 0, "", "", st.error()}};
  std::snprintf(note, sizeof note, "%d implicit frames of %d at %d^3: sample %.2f s + redistance, write %.0f ms (%.1f MB, %.0fk voxels sampled/frame)",
                volumes, count, res, sampleMs / 1000.0, vdbWriteMs, vdbBytes / 1e6,
                volumes ? double(voxels) / volumes / 1000.0 : 0.0);
  rows.push_back({"demo -> VDB level sets", (sampleMs + vdbWriteMs) / 1000.0, "s", "", note});
  std::snprintf(note, sizeof note, "baseline: the same %d frames polygonised + written as PLY %.2f s: VDB %.2fx", volumes,
                meshMs / 1000.0, meshMs > 0.0 ? (sampleMs + vdbWriteMs) / meshMs : 0.0);
  rows.push_back({"demo -> PLY (same frames)", meshMs / 1000.0, "s", "", note});
  return rows;
}

}  // namespace

ANIMORPH_BENCH("export", "bake the demo morph and write it as an animated glTF (baseline: a PLY sequence) and as VDB level sets (baseline: PLY)", benchExport);
