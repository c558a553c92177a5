// animorph-cli bake PROJECT --frames A:B --res N -o DIR [--format ...] [--gltf FILE.glb] [--vdb DIR] [--png] [--jobs J] [--coherence C]:
// the morph's output meshes as a PLY/OBJ sequence and/or one animated glTF, its implicit frames
// as OpenVDB level sets (and optionally rendered PNG frames), frame by frame.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <mutex>
#include <thread>

#include "core/animorphosis/evaluate_generic.h"
#include "core/export/frame_files.h"
#include "core/export/frame_stage.h"
#include "core/export/frame_volume.h"
#include "app/cli/cli_command.h"
#include "app/cli/morph_method_option.h"
#include "app/cli/playblast.h"
#include "app/cli/progress_bar.h"
#include "core/project/animorphosis_project.h"
#include "core/poly/frame_sequence.h"
#include "core/poly/polygonizer.h"
#include "core/scene/mesh_character.h"
#include "core/project/project_io.h"
#include "core/standin_morph/morph_continuity.h"
#include "core/scene/morph_runtime.h"
#include "core/io/gltf_sequence_export.h"
#include "core/io/vdb_export.h"
#include "core/io/mesh_io.h"
#include "gpu/vulkan/context.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/render/mesh_cache.h"
#include "gpu/present/offscreen_target.h"
#include "gpu/frame/scene_from_frame.h"
#include "gpu/render/scene_renderer.h"
#include "core/camera/camera.h"
#include "core/scene/morph_smoothness.h"
#include "core/scene/visible_surface.h"

namespace {

using namespace animorph;
using cli::PictureOptions;
using cli::ProgressBar;
namespace fs = std::filesystem;

// Runs frame(k) for k = 0..count-1 on up to `jobs` threads under a progress bar; frame returns an
// error message, or "" on success. Returns the error of the first failing frame, naming it.
std::string bakeFrames(int first, int count, int jobs, const std::function<std::string(int)>& frame) {
  std::vector<std::string> errors(static_cast<size_t>(count));
  std::atomic<int> next{0};
  ProgressBar bar("baking", count);
  auto worker = [&] {
    for (int k = next.fetch_add(1); k < count; k = next.fetch_add(1)) {
      errors[size_t(k)] = frame(k);
      bar.step();
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < std::min(jobs, count); ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  for (int k = 0; k < count; ++k)
    if (!errors[size_t(k)].empty()) return "frame " + std::to_string(first + k) + ": " + errors[size_t(k)];
  return {};
}

// Where baked frames go, from any worker thread: the per-frame files (DIR/NAME_####.ply, .obj),
// the animated glTF (fed in frame order: a finished frame waits here until the frames before it
// have been added), and the meshes kept for --png.
class FrameSink {
 public:
  struct Options {
    fs::path dir;
    std::string prefix;
    bool plys = true, objs = false, png = false;
    bool keep = false;  // keep every frame's mesh (for --png and --mp4)
    std::string gltf;  // empty: none
    fs::path vdb;      // the folder of the level sets; empty: none
    double fps = 24.0;
    int first = 0, count = 0;
  };
  explicit FrameSink(Options o) : o_(std::move(o)), kept(o_.keep ? size_t(o_.count) : 0u) {
    if (o_.gltf.empty()) return;
    GltfSequenceOptions so;
    so.name = o_.prefix;
    so.fps = o_.fps;
    so.firstFrame = o_.first;
    sequence_ = std::make_unique<GltfSequenceWriter>(so);
    ready_.resize(size_t(o_.count));
    done_.assign(size_t(o_.count), 0);
  }

  // Frame first + k is baked: writes its files; "" or the error.
  std::string add(int k, TriangleMesh mesh) {
    const int f = o_.first + k;
    Status st;
    if (o_.plys) st = writePly(mesh, frameFileName(o_.dir.string(), o_.prefix, f, "ply"));
    if (st && o_.objs) st = writeObj(mesh, frameFileName(o_.dir.string(), o_.prefix, f, "obj"));
    if (!st) return st.error();
    if (sequence_) {
      std::lock_guard<std::mutex> lock(sequenceMutex_);
      ready_[size_t(k)] = o_.keep ? mesh : std::move(mesh);
      done_[size_t(k)] = 1;
      for (; next_ < o_.count && done_[size_t(next_)]; ++next_) {
        if (Status added = sequence_->addFrame(ready_[size_t(next_)]); !added && sequenceError_.empty())
          sequenceError_ = "frame " + std::to_string(o_.first + next_) + ": " + added.error();
        ready_[size_t(next_)] = TriangleMesh{};
      }
    }
    if (o_.keep) kept[size_t(k)] = std::move(mesh);
    return {};
  }

  bool wantsVolumes() const { return !o_.vdb.empty(); }
  // Frame first + k's level set (null: the frame has no implicit field): writes
  // VDB/NAME_####.vdb; "" or the error.
  std::string addVolume(int k, const LevelSetVoxels* band) {
    if (!band) {
      ++volumesSkipped_;
      return {};
    }
    if (Status st = writeVdbLevelSet(*band, frameFileName(o_.vdb.string(), o_.prefix, o_.first + k, "vdb")); !st)
      return st.error();
    ++volumesWritten_;
    return {};
  }

  // After every frame: says what went into the VDB folder, writes the glTF (atomically) and says
  // so; "" or the error.
  std::string finish() {
    if (!o_.vdb.empty()) {
      std::printf("wrote %d OpenVDB level sets into %s (%s_####.vdb)", int(volumesWritten_), o_.vdb.c_str(),
                  o_.prefix.c_str());
      if (volumesSkipped_ > 0)
        std::printf("; %d frames are skinned meshes without an implicit field: no .vdb for them", int(volumesSkipped_));
      std::printf("\n");
      if (volumesWritten_ == 0) return "--vdb: no frame of the range has an implicit field (the morph's B->C stage)";
    }
    if (!sequence_) return {};
    if (!sequenceError_.empty()) return sequenceError_;
    const auto g0 = std::chrono::steady_clock::now();
    const int meshes = sequence_->meshCount();
    if (Status st = writeGltfSequence(*sequence_, o_.gltf); !st) return st.error();
    std::error_code ec;
    std::printf("wrote %s: %d frames, %d distinct meshes, %.1f MB at %g fps in %.2f s\n", o_.gltf.c_str(), o_.count,
                meshes, double(fs::file_size(o_.gltf, ec)) / 1e6, o_.fps,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - g0).count());
    return {};
  }

  const std::string& prefix() const { return o_.prefix; }
  // Where the frames went, for the summary line.
  std::string into() const {
    std::string s = o_.plys || o_.objs || o_.png ? o_.dir.string() : std::string();
    if (!o_.gltf.empty()) s += (s.empty() ? "" : " and ") + o_.gltf;
    if (!o_.vdb.empty()) s += (s.empty() ? "" : " and ") + o_.vdb.string();
    return s;
  }

 private:
  Options o_;
  std::unique_ptr<GltfSequenceWriter> sequence_;
  std::mutex sequenceMutex_;
  std::vector<TriangleMesh> ready_;
  std::vector<char> done_;
  int next_ = 0;
  std::string sequenceError_;
  std::atomic<int> volumesWritten_{0}, volumesSkipped_{0};

 public:
  std::vector<TriangleMesh> kept;  // with keep: every frame's mesh, for renderPictures
};


// A project whose only transformation is an animorphosis: C(t) polygonised frame by frame (CPU), in
// the trees' own space; with --png, rendered like the morph's frames. coherence > 0: the frames in
// order on one grid with temporal coherence (poly/frame_sequence.h), each vertex within `coherence`
// cells of a full polygonisation's; 0: every frame on its own grid, frames in parallel over jobs.
int bakeAnimorphosis(const Project& p, const std::string& project, FrameSink& sink, int first, int last, int res,
                     int jobs, float coherence, const PictureOptions& pics, const std::string& output) {
  auto c = projectGenericTree(p);
  if (!c) return cli::fail("bake", project + ": " + c.error());
  const AnimorphosisTiming timing = animorphosisTiming(p);
  const auto t0 = std::chrono::steady_clock::now();
  const int count = last - first + 1;
  std::atomic<size_t> triangles{0};
  // One frame's field, and what it adds to the sink (its level set first); "" or the error.
  auto finishFrame = [&](int k, const FieldProgram& field, TriangleMesh&& mesh, int threads) -> std::string {
    if (sink.wantsVolumes()) {
      auto band = fieldLevelSet(field, res, threads, nullptr);
      if (!band) return band.error();
      if (std::string e = sink.addVolume(k, &**band); !e.empty()) return e;
    }
    triangles += mesh.triangleCount();
    return sink.add(k, std::move(mesh));
  };
  auto programOf = [&](int k) { return compileGeneric(*c, timing, p.timeline.frameToSec(first + k)); };
  std::string error, coherenceNote;
  if (coherence > 0.0f) {
    FrameSequenceSettings fs;
    fs.resolution = res;
    fs.reuseToleranceCells = coherence;
    fs.colors = true;
    ProgressBar bar("baking", count);
    auto stats = polygonizeFrameSequence(
        count, programOf,
        [&](int k, PolygonizeResult&& r) -> Status {
          std::string e = sink.wantsVolumes() ? finishFrame(k, programOf(k), std::move(r.mesh), 0)
                                              : finishFrame(k, FieldProgram{}, std::move(r.mesh), 0);
          bar.step();
          if (!e.empty()) return Error{"frame " + std::to_string(first + k) + ": " + e};
          return {};
        },
        fs);
    if (!stats) error = stats.error();
    else
      coherenceNote = "; temporal coherence (" + std::to_string(coherence).substr(0, 4) + " cell): " +
                      std::to_string(stats->blocksReused) + " of " + std::to_string(stats->blocksEvaluated) +
                      " blocks reused, one " + std::to_string(stats->grid.cells[0]) + "x" +
                      std::to_string(stats->grid.cells[1]) + "x" + std::to_string(stats->grid.cells[2]) + " grid";
  } else {
    error = bakeFrames(first, count, jobs, [&](int k) -> std::string {
      PolygonizeSettings ps;
      ps.resolution = res;
      ps.threads = jobs > 1 ? 1 : 0;
      ps.colors = true;
      const FieldProgram field = programOf(k);
      auto r = polygonize(field, ps);
      if (!r) return r.error();
      return finishFrame(k, field, std::move(r->mesh), ps.threads);
    });
  }
  if (!error.empty()) return cli::fail("bake", error);
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("baked the animorphosis %s -> %s, frames %d..%d (%zu nodes, %zu triangles in all) at %d^3 into %s in %.2f s%s\n",
              p.animorphosis.sourceActorId.c_str(), p.animorphosis.targetActorId.c_str(), first, last, c->size(),
              size_t(triangles), res, sink.into().c_str(), sec, coherenceNote.c_str());
  if (std::string e = sink.finish(); !e.empty()) return cli::fail("bake", e);
  if (int code = renderPictures(sink.kept, first, output, sink.prefix(), p.view, pics); code != 0) return code;
  return 0;
}

int runBake(const std::vector<std::string>& args) {
  std::string project, output, frames, name, gltf, vdb, mp4, size = "1280x720", format = "ply";
  int res = 48, jobs = 1;
  float coherence = 0.1f;  // an animorphosis' temporal coherence tolerance (cells); 0: off
  bool png = false, gpu = false, burnIn = false, keepInnerShell = false;
  cli::MorphMethodOptions methods;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string* { return i + 1 < args.size() ? &args[++i] : nullptr; };
    if (a == "-o" || a == "--output" || a == "--frames" || a == "--res" || a == "--jobs" || a == "--name" ||
        a == "--format" || a == "--gltf" || a == "--vdb" || a == "--mp4" || a == "--size" || a == "--coherence") {
      const std::string* v = value();
      if (!v) return cli::fail("bake", a + " needs a value", 2);
      if (a == "--frames") frames = *v;
      else if (a == "--res") res = std::atoi(v->c_str());
      else if (a == "--jobs") jobs = std::atoi(v->c_str());
      else if (a == "--name") name = *v;
      else if (a == "--format") format = *v;
      else if (a == "--gltf") gltf = *v;
      else if (a == "--vdb") vdb = *v;
      else if (a == "--mp4") mp4 = *v;
      else if (a == "--size") size = *v;
      else if (a == "--coherence") {
        char* end = nullptr;
        coherence = std::strtof(v->c_str(), &end);
        if (end == v->c_str() || *end != '\0' || !(coherence >= 0.0f && coherence <= 0.5f))
          return cli::fail("bake", "--coherence: expected a tolerance in cells, 0..0.5 (0: off), got '" + *v + "'", 2);
      } else output = *v;
    } else if (a == "--obj") {
      format = "obj";
    } else if (a == "--png") {
      png = true;
    } else if (a == "--burn-in") {
      burnIn = true;
    } else if (a == "--keep-inner-shell") {
      keepInnerShell = true;
    } else if (a == "--gpu") {
      gpu = true;
    } else if (std::string err; cli::readMorphMethodOption(args, i, methods, err)) {
      if (!err.empty()) return cli::fail("bake", err, 2);
    } else if (!a.empty() && a[0] == '-') {
      return cli::fail("bake", "unknown option " + a, 2);
    } else if (project.empty()) {
      project = a;
    } else {
      return cli::fail("bake", "only one PROJECT is accepted", 2);
    }
  }
  bool writePlys = false, writeObjs = false;
  if (format != "none") {
    for (size_t at = 0; at <= format.size();) {
      const size_t comma = std::min(format.find(',', at), format.size());
      const std::string f = format.substr(at, comma - at);
      if (f == "ply") writePlys = true;
      else if (f == "obj") writeObjs = true;
      else return cli::fail("bake", "--format: expected ply, obj, ply,obj or none, got '" + format + "'", 2);
      at = comma + 1;
    }
  }
  const bool needDir = writePlys || writeObjs || png;
  int width = 0, height = 0;
  char sizeTail = 0;
  if (std::sscanf(size.c_str(), "%dx%d%c", &width, &height, &sizeTail) != 2 || width < 16 || height < 16 ||
      width > 8192 || height > 8192 || width % 2 || height % 2)
    return cli::fail("bake", "--size: expected WxH, even numbers 16..8192 (H.264 needs even sizes), got '" + size + "'", 2);
  if (project.empty() || frames.empty() || (needDir && output.empty()) || (!needDir && gltf.empty() && vdb.empty() && mp4.empty()))
    return cli::fail("bake", "usage: bake PROJECT --frames A:B --res N -o DIR [--format ply|obj|none] [--gltf FILE.glb] [--vdb DIR] (see --help)", 2);
  if (!name.empty() && framePrefix(name) != name)
    return cli::fail("bake", "--name: use letters, digits, '.', '-' and '_' only, got '" + name + "'", 2);
  int first = 0, last = 0;
  char tail = 0;
  if (std::sscanf(frames.c_str(), "%d:%d%c", &first, &last, &tail) != 2 || first < 0 || last < first)
    return cli::fail("bake", "--frames: expected A:B with 0 <= A <= B, got '" + frames + "'", 2);
  if (res < 2 || res > 1024) return cli::fail("bake", "--res: expected 2..1024", 2);
  if (jobs < 1 || jobs > 256) return cli::fail("bake", "--jobs: expected 1..256", 2);

  auto p = loadProject(project);
  if (!p) return cli::fail("bake", p.error());
  cli::applyMorphMethodOptions(methods, p->morph);
  const std::string prefix = name.empty() ? framePrefix(p->name) : name;
  std::error_code ec;
  if (needDir) fs::create_directories(output, ec);
  if (ec) return cli::fail("bake", output + ": cannot create directory: " + ec.message());
  if (!gltf.empty() && fs::path(gltf).has_parent_path()) fs::create_directories(fs::path(gltf).parent_path(), ec);
  if (ec) return cli::fail("bake", gltf + ": cannot create its directory: " + ec.message());
  if (!vdb.empty()) fs::create_directories(vdb, ec);
  if (ec) return cli::fail("bake", vdb + ": cannot create the VDB directory: " + ec.message());
  const int count = last - first + 1;
  PictureOptions pics;
  pics.png = png;
  pics.mp4 = mp4;
  pics.burnIn = burnIn;
  pics.stages = frameStageSpans(*p, first, last);
  pics.fps = p->timeline.fps;
  pics.width = uint32_t(width);
  pics.height = uint32_t(height);
  if (!mp4.empty() && fs::path(mp4).has_parent_path()) fs::create_directories(fs::path(mp4).parent_path(), ec);
  if (ec) return cli::fail("bake", mp4 + ": cannot create its directory: " + ec.message());
  FrameSink sink({output, prefix, writePlys, writeObjs, png, png || !mp4.empty(), gltf, vdb, p->timeline.fps, first, count});
  if (!p->morph.enabled() && p->animorphosis.enabled()) {
    if (gpu) return cli::fail("bake", "--gpu: an animorphosis is baked on the CPU (run without --gpu)", 2);
    return bakeAnimorphosis(*p, project, sink, first, last, res, jobs, coherence, pics, output);
  }
  const std::string baseDir = fs::absolute(fs::path(project)).parent_path().string();
  AssetCache assets;
  auto rt = prepareMorph(*p, baseDir, assets);
  if (!rt) return cli::fail("bake", project + ": " + rt.error());
  for (const auto& n : (*rt)->notes) std::printf("note: %s\n", n.c_str());

  // --gpu: the B->C stage on the Vulkan compute polygoniser (one device, its
  // frames one at a time); the other stages are the same as on the CPU. No
  // device, or a device failure, is an error: no silent fallback to the CPU.
  std::unique_ptr<gpu::Context> gpuCtx;
  std::unique_ptr<gpu::GpuPolygonizer> gpuPoly;
  std::mutex gpuMutex;
  if (gpu) {
    auto c = gpu::Context::create(gpu::ContextSettings{});
    if (!c) return cli::fail("bake", "--gpu: no usable Vulkan device: " + c.error());
    gpuCtx = std::move(*c);
    auto poly = gpu::GpuPolygonizer::create(*gpuCtx);
    if (!poly) return cli::fail("bake", "--gpu: " + poly.error());
    gpuPoly = std::move(*poly);
    std::printf("B->C polygonised on the GPU: %s\n", gpuCtx->deviceName().c_str());
  }
  // The B->C frame at timeSec polygonised on the GPU (same field and grid as the CPU's).
  auto gpuMorphFrame = [&](double timeSec) -> Result<MorphFrame> {
    MorphFrame fr;
    fr.timeSec = timeSec;
    fr.stage = MorphStage::Morph;
    MorphImplicitField field = morphImplicitField(**rt, timeSec, res);
    fr.progress = field.progress;
    fr.blend = field.blend;
    gpu::GpuField gf = gpu::GpuField::single(field.program);
    if (std::string why = gpu::GpuPolygonizer::unsupported(gf); !why.empty())
      return Error{"the GPU polygoniser cannot evaluate this morph: " + why};
    gpu::GpuPolygonizeSettings gs;
    gs.resolution = res;
    gs.bounds = field.bounds;
    gs.noiseAmplitude = field.noiseAmplitude;  // the GPU's noise pass: the CPU path's displacement
    gs.noiseFrequency = (*rt)->setup.noiseFrequency;
    std::lock_guard<std::mutex> lock(gpuMutex);
    auto stats = gpuPoly->polygonize(gf, gs);
    if (!stats) return Error{stats.error()};
    auto mesh = gpuPoly->readBack();
    if (!mesh) return Error{mesh.error()};
    fr.mesh = std::move(*mesh);
    fr.polygonize.gridX = stats->gridX;
    fr.polygonize.gridY = stats->gridY;
    fr.polygonize.gridZ = stats->gridZ;
    fr.polygonize.cellSize = stats->cellSize;
    fr.polygonize.blocksTotal = stats->blocksTotal;
    fr.polygonize.blocksEvaluated = stats->blocksActive;
    fr.polygonize.blocksCulled = stats->blocksTotal - stats->blocksActive;
    fr.polygonize.milliseconds = stats->milliseconds;
    return fr;
  };

  const auto t0 = std::chrono::steady_clock::now();
  std::vector<int> stageCount(5, 0);
  std::vector<FrameMeasure> measures(static_cast<size_t>(count));  // per frame, for the continuity report
  std::mutex stageMutex;
  // The continuity ratio's frames: the range's part of A..D.
  const MorphMarkers& marks = (*rt)->setup.markers;
  const int ratioFirst = std::max(first, marks.a), ratioLast = std::min(last, marks.d);
  FrameJumpMeter jumps(ratioFirst, ratioLast);
  std::atomic<int> coreFrames{0};
  std::string error = bakeFrames(first, count, jobs, [&](int k) -> std::string {
    const int f = first + k;
    MorphFrameSettings fs;
    fs.resolution = res;
    fs.threads = jobs > 1 ? 1 : 0;
    const double timeSec = p->timeline.frameToSec(f);
    double u = 0.0;
    const bool onGpu = gpu && morphStageAt((*rt)->setup, (*rt)->timeline, timeSec, u) == MorphStage::Morph;
    auto fr = onGpu ? gpuMorphFrame(timeSec) : evaluateMorphFrame(**rt, timeSec, fs);
    if (!fr) return fr.error();
    {
      std::lock_guard<std::mutex> lock(stageMutex);
      ++stageCount[size_t(fr->stage)];
    }
    measures[size_t(k)] = measureFrame(f, fr->mesh, nullptr, fr->coreTriangles);
    // A collapse or expansion frame is two closed shells, the mesh and the stand-in core inside it:
    // the file gets what is seen (their union's boundary) unless --keep-inner-shell.
    TriangleMesh visible = fr->coreTriangles > 0 ? visibleSurface(**rt, *fr) : fr->mesh;
    coreFrames += fr->coreTriangles > 0;
    if (f >= ratioFirst && f <= ratioLast) jumps.add(f, visible);
    if (!keepInnerShell) fr->mesh = std::move(visible);
    if (sink.wantsVolumes()) {
      auto band = morphFrameLevelSet(**rt, timeSec, res, fs.threads, nullptr);
      if (!band) return band.error();
      if (std::string e = sink.addVolume(k, *band ? &**band : nullptr); !e.empty()) return e;
    }
    return sink.add(k, std::move(fr->mesh));
  });
  if (!error.empty()) return cli::fail("bake", error);
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("baked frames %d..%d (%d source, %d collapse, %d morph, %d expand, %d target) at %d^3 into %s in %.2f s\n",
              first, last, stageCount[0], stageCount[1], stageCount[2], stageCount[3], stageCount[4], res,
              sink.into().c_str(), sec);
  const std::vector<ContinuityDefect> defects = continuityDefects(measures);
  std::printf("continuity: %zu frame%s empty or changing volume by more than %.0f%% from the frame before\n",
              defects.size(), defects.size() == 1 ? "" : "s", 100.0 * kMaxFrameVolumeChange);
  for (const ContinuityDefect& d : defects) std::printf("  frame %d: %s\n", d.frame, d.reason.c_str());
  {  // the largest change, over the range and within B..C (the implicit stage, seams left out)
    const MorphMarkers& mk = (*rt)->setup.markers;
    double all = 0.0, inside = 0.0;
    int atAll = first, atInside = -1;
    for (size_t k = 1; k < measures.size(); ++k) {
      const double d = relativeVolumeChange(measures[k - 1].volume, measures[k].volume);
      if (d > all) all = d, atAll = measures[k].frame;
      if (measures[k - 1].frame >= mk.b && measures[k].frame <= mk.c && d >= inside) inside = d, atInside = measures[k].frame;
    }
    std::printf("continuity: %s, largest frame-to-frame volume change %.1f%% at frame %d", morphMethodName((*rt)->setup.method),
                100.0 * all, atAll);
    if (atInside >= 0) std::printf(", within B..C %.1f%% at frame %d", 100.0 * inside, atInside);
    std::printf("\n");
  }
  if (ratioLast > ratioFirst) {  // the visible surface's largest jump against the characters' own motion
    ContinuityRatio r;
    r.first = ratioFirst;
    r.last = ratioLast;
    r.jump = jumps.largestJump();
    r.jumpFrame = jumps.largestJumpFrame();
    r.motion = charactersOwnMotion(**rt, ratioFirst, ratioLast, res);
    std::printf("continuity ratio (largest frame-to-frame jump of the visible surface / the characters' own largest "
                "motion, bound %.0f): %s%s\n",
                kMaxContinuityRatio, r.describe().c_str(),
                ratioFirst == marks.a && ratioLast == marks.d ? " (A..D)" : " (the range's part of A..D)");
    std::vector<std::pair<int, double>> largest = jumps.jumps();
    std::sort(largest.begin(), largest.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
    std::printf("continuity ratio: the largest jumps:");
    for (size_t i = 0; i < std::min<size_t>(5, largest.size()); ++i)
      std::printf(" frame %d %.2fx,", largest[i].first,
                  r.motion.hausdorff > 0.0 ? largest[i].second / r.motion.hausdorff : 0.0);
    std::printf(" (stages: collapse %d..%d, morph %d..%d, expansion %d..%d)\n", marks.a, marks.b, marks.b, marks.c,
                marks.c, marks.d);
  }
  if (coreFrames > 0)
    std::printf(keepInnerShell ? "note: %d collapse / expansion frames carry the stand-in core as a second closed shell "
                                 "inside the mesh (--keep-inner-shell)\n"
                               : "note: %d collapse / expansion frames written as their visible surface: the stand-in "
                                 "core inside the mesh cut away (--keep-inner-shell keeps both shells)\n",
                int(coreFrames));
  if (std::string e = sink.finish(); !e.empty()) return cli::fail("bake", e);
  if (gpuCtx && gpuCtx->validationEnabled() && gpuCtx->validationErrorCount() > 0) {
    std::fprintf(stderr, "animorph-cli bake: %u Vulkan validation error(s) in the GPU polygoniser\n",
                 gpuCtx->validationErrorCount());
    return 3;
  }
  if (int code = renderPictures(sink.kept, first, output, prefix, p->view, pics); code != 0) return code;
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("bake", "bake a project's morph into mesh sequences, an animated glTF, VDB level sets (and PNG frames)",
                     "usage: animorph-cli bake PROJECT.animorph --frames A:B --res N -o DIR [--format ply|obj|ply,obj|none]\n"
                     "                         [--obj] [--name NAME] [--gltf FILE.glb] [--vdb DIR] [--png] [--mp4 FILE.mp4 [--size WxH]\n"
                     "                         [--burn-in]] [--gpu] [--jobs J] [--coherence C] [--method M [--correspondence-blend B]]\n"
                     "                         [--keep-inner-shell]\n"
                     "  Bakes every frame A..B: the source's skinned mesh before marker A, its\n"
                     "  collapse onto the stand-in A->B, the polygonised implicit morph B->C (N cells\n"
                     "  along the longest side), the target's expansion C->D and its skinned mesh\n"
                     "  after D; world space, unit normals. A project whose only transformation is an\n"
                     "  animorphosis of two BlobTrees bakes its C(t) instead (CPU, in the trees' own space).\n"
                     "  --format F   the mesh sequence written into DIR, one file per frame named\n"
                     "               NAME_####.ply / NAME_####.obj (frame number padded to 4 digits):\n"
                     "               ply (binary PLY, the default), obj (Wavefront OBJ with vn normals,\n"
                     "               f a//a b//b c//c faces, v x y z r g b when the frame has vertex\n"
                     "               colours), ply,obj (both) or none (no sequence; -o not needed then)\n"
                     "  --obj        short for --format obj\n"
                     "  --name NAME  the file-name prefix (default: the project's name)\n"
                     "  --gltf FILE  also one animated glTF binary of the whole range: a mesh per\n"
                     "               frame (identical frames share one), each frame's node shown only\n"
                     "               on its frame by STEP scale keys 0 -> 1 -> 0 at frame/fps seconds\n"
                     "               (fps of the project's timeline), plus KHR_node_visibility keys\n"
                     "               (optional extension). Written atomically.\n"
                     "  --vdb DIR    also DIR/NAME_####.vdb: the implicit field of every frame that has\n"
                     "               one (B->C; a BlobTree side; an animorphosis' C(t)) as an OpenVDB\n"
                     "               level set: grid 'surface', narrow band of 3 voxels on the grid of\n"
                     "               --res, signed distance in world units, negative inside (see\n"
                     "               docs/export.md). Skinned-mesh frames have no field: no file\n"
                     "  --png        also DIR/NAME_####.png, rendered offscreen (Vulkan; set\n"
                     "               ANIMORPH_VALIDATION=1 for validation layers)\n"
                     "  --mp4 FILE   also a playblast: every frame rendered offscreen (Vulkan) at --size\n"
                     "               (default 1280x720, even numbers) and encoded by ffmpeg (H.264, the\n"
                     "               timeline's fps); written under a temporary name, renamed when done\n"
                     "  --burn-in    the frame number and the morph's stage (before A, A..B, B..C, C..D,\n"
                     "               after D; animorphosis for an animorphosis) drawn into the\n"
                     "               playblast's top-left corner\n"
                     "  --gpu        the B->C stage on the Vulkan compute polygoniser (offscreen, no\n"
                     "               display needed); exits 1 with a message when no device is usable\n"
                     "               or the device fails (no silent fallback to the CPU)\n"
                     "  --jobs J     frames baked in parallel (the output is the same for any J; an\n"
                     "               animorphosis with --coherence above 0 bakes its frames in order)\n"
                     "  --coherence C  an animorphosis: its frames polygonised in order on one grid (the\n"
                     "               union of the frames' own grids, at the finest of their cells), a\n"
                     "               block reused from the frame before when the field provably moved\n"
                     "               there so little that the block's corners keep their signs and its\n"
                     "               vertices stay within C cells of a full polygonisation's (same\n"
                     "               triangles); default 0.1, 0 = off (each frame on its own grid)\n"
                     "  --method M   bake with another morph method than the project's: interpolation,\n"
                     "               space_time or skeleton_correspondence (--correspondence-blend B:\n"
                     "               interpolation or space_time, how it combines its two stand-ins)\n"
                     "  --keep-inner-shell  collapse and expansion frames are the transitioned mesh with\n"
                     "               the stand-in core inside it, two closed shells; by default a frame\n"
                     "               is written as what is seen, the boundary of their union (the mesh\n"
                     "               cut where it enters the core, the core cut where it enters the\n"
                     "               mesh); this keeps both shells whole\n"
                     "  A progress bar is drawn when stdout is a terminal. Then a continuity report:\n"
                     "  frames that are empty or whose enclosed volume changes by more than 20% from\n"
                     "  the frame before (what shows as a pop); they do not change the exit status;\n"
                     "  and the largest frame-to-frame volume change, over the frames and within B..C;\n"
                     "  and the continuity ratio: the largest frame-to-frame jump (Hausdorff distance)\n"
                     "  of the visible surface over the range's part of A..D, divided by the\n"
                     "  characters' own largest per-frame motion over the same frames (at most 2 holds\n"
                     "  no pop, docs/morph.md).\n"
                     "  Exit status: 0 on success, 1 when the project cannot be read or a frame fails,\n"
                     "  2 on bad arguments, 3 on Vulkan validation errors.\n",
                     runBake);
