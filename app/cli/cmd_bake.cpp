// animorph-cli bake PROJECT --frames A:B --res N -o DIR [--format ...] [--gltf FILE.glb] [--vdb DIR] [--png] [--jobs J] [--coherence C]:
// the morph's output meshes as a PLY/OBJ sequence and/or one animated glTF, its implicit frames
// as OpenVDB level sets (and optionally rendered PNG frames), frame by frame. The arguments and
// the report; the baking is the one route File > Export... and the playblast take too
// (export/bake_route.h), with the GPU polygoniser plugged in for --gpu.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "app/cli/cli_command.h"
#include "app/cli/gpu_implicit_stage.h"
#include "app/cli/morph_method_option.h"
#include "app/cli/playblast.h"
#include "app/cli/progress_bar.h"
#include "core/export/bake_route.h"
#include "core/export/frame_files.h"
#include "core/export/frame_stage.h"
#include "core/export/project_frames.h"
#include "core/project/project_io.h"
#include "core/scene/morph_smoothness.h"

namespace {

using namespace animorph;
using cli::PictureOptions;
using cli::ProgressBar;
namespace fs = std::filesystem;

// bake's arguments, as given and as checked.
struct BakeArgs {
  std::string project, output, frames, name, gltf, vdb, mp4, size = "1280x720", format = "ply";
  int res = 48, jobs = 1;
  float coherence = 0.1f;  // an animorphosis' temporal coherence tolerance (cells); 0: off
  bool png = false, gpu = false, burnIn = false, keepInnerShell = false, noColor = false;
  cli::MorphMethodOptions methods;
  // From the above:
  bool writePlys = false, writeObjs = false;
  int first = 0, last = 0, width = 0, height = 0;
  bool needDir() const { return writePlys || writeObjs || png; }
};

// The options that take a value; "" or the usage error (exit status 2).
std::string readValueOption(const std::string& a, const std::string& v, BakeArgs& o) {
  if (a == "--frames") o.frames = v;
  else if (a == "--res") o.res = std::atoi(v.c_str());
  else if (a == "--jobs") o.jobs = std::atoi(v.c_str());
  else if (a == "--name") o.name = v;
  else if (a == "--format") o.format = v;
  else if (a == "--gltf") o.gltf = v;
  else if (a == "--vdb") o.vdb = v;
  else if (a == "--mp4") o.mp4 = v;
  else if (a == "--size") o.size = v;
  else if (a == "--coherence") {
    char* end = nullptr;
    o.coherence = std::strtof(v.c_str(), &end);
    if (end == v.c_str() || *end != '\0' || !(o.coherence >= 0.0f && o.coherence <= 0.5f))
      return "--coherence: expected a tolerance in cells, 0..0.5 (0: off), got '" + v + "'";
  } else o.output = v;
  return {};
}

// Reads args into o; "" or the usage error (exit status 2).
std::string readArgs(const std::vector<std::string>& args, BakeArgs& o) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-o" || a == "--output" || a == "--frames" || a == "--res" || a == "--jobs" || a == "--name" ||
        a == "--format" || a == "--gltf" || a == "--vdb" || a == "--mp4" || a == "--size" || a == "--coherence") {
      if (i + 1 >= args.size()) return a + " needs a value";
      if (std::string e = readValueOption(a, args[++i], o); !e.empty()) return e;
    } else if (a == "--obj") {
      o.format = "obj";
    } else if (a == "--png") {
      o.png = true;
    } else if (a == "--burn-in") {
      o.burnIn = true;
    } else if (a == "--no-color") {
      o.noColor = true;
    } else if (a == "--keep-inner-shell") {
      o.keepInnerShell = true;
    } else if (a == "--gpu") {
      o.gpu = true;
    } else if (std::string err; cli::readMorphMethodOption(args, i, o.methods, err)) {
      if (!err.empty()) return err;
    } else if (!a.empty() && a[0] == '-') {
      return "unknown option " + a;
    } else if (o.project.empty()) {
      o.project = a;
    } else {
      return "only one PROJECT is accepted";
    }
  }
  return {};
}

// Checks the arguments read and derives the rest; "" or the usage error (exit status 2).
std::string checkArgs(BakeArgs& o) {
  if (o.format != "none") {
    for (size_t at = 0; at <= o.format.size();) {
      const size_t comma = std::min(o.format.find(',', at), o.format.size());
      const std::string f = o.format.substr(at, comma - at);
      if (f == "ply") o.writePlys = true;
      else if (f == "obj") o.writeObjs = true;
      else return "--format: expected ply, obj, ply,obj or none, got '" + o.format + "'";
      at = comma + 1;
    }
  }
  char sizeTail = 0;
  if (std::sscanf(o.size.c_str(), "%dx%d%c", &o.width, &o.height, &sizeTail) != 2 || o.width < 16 || o.height < 16 ||
      o.width > 8192 || o.height > 8192 || o.width % 2 || o.height % 2)
    return "--size: expected WxH, even numbers 16..8192 (H.264 needs even sizes), got '" + o.size + "'";
  // --format none with no other output is a bake that writes nothing: its report only (timing, continuity).
  if (o.project.empty() || o.frames.empty() || (o.needDir() && o.output.empty()))
    return "usage: bake PROJECT --frames A:B --res N -o DIR [--format ply|obj|none] [--gltf FILE.glb] [--vdb DIR] (see --help)";
  if (!o.name.empty() && framePrefix(o.name) != o.name)
    return "--name: use letters, digits, '.', '-' and '_' only, got '" + o.name + "'";
  char tail = 0;
  if (std::sscanf(o.frames.c_str(), "%d:%d%c", &o.first, &o.last, &tail) != 2 || o.first < 0 || o.last < o.first)
    return "--frames: expected A:B with 0 <= A <= B, got '" + o.frames + "'";
  if (o.res < 2 || o.res > 1024) return "--res: expected 2..1024";
  if (o.jobs < 1 || o.jobs > 256) return "--jobs: expected 1..256";
  return {};
}

// The outputs' folders, each error naming the folder as given; "" or the error.
std::string makeFolders(const BakeArgs& o) {
  std::error_code ec;
  if (o.needDir()) fs::create_directories(o.output, ec);
  if (ec) return o.output + ": cannot create directory: " + ec.message();
  if (!o.gltf.empty() && fs::path(o.gltf).has_parent_path()) fs::create_directories(fs::path(o.gltf).parent_path(), ec);
  if (ec) return o.gltf + ": cannot create its directory: " + ec.message();
  if (!o.vdb.empty()) fs::create_directories(o.vdb, ec);
  if (ec) return o.vdb + ": cannot create the VDB directory: " + ec.message();
  if (!o.mp4.empty() && fs::path(o.mp4).has_parent_path()) fs::create_directories(fs::path(o.mp4).parent_path(), ec);
  if (ec) return o.mp4 + ": cannot create its directory: " + ec.message();
  return {};
}

// The route's settings for these arguments (the GPU polygoniser is plugged in by the caller).
BakeSettings bakeSettings(const BakeArgs& o, const std::string& prefix) {
  BakeSettings s;
  s.first = o.first;
  s.last = o.last;
  s.resolution = o.res;
  s.jobs = o.jobs;
  s.coherence = o.coherence;
  s.keepInnerShell = o.keepInnerShell;
  s.colors = !o.noColor;
  s.outputs.prefix = prefix;
  s.outputs.dir = o.output;
  s.outputs.ply = o.writePlys;
  s.outputs.obj = o.writeObjs;
  s.outputs.gltf = o.gltf;
  s.outputs.vdbDir = o.vdb;
  s.outputs.keepMeshes = o.png || !o.mp4.empty();
  s.measureContinuity = true;
  return s;
}

// Where the frames went, for the summary line.
std::string into(const BakeArgs& o) {
  std::string s = o.needDir() ? o.output : std::string();
  if (!o.gltf.empty()) s += (s.empty() ? "" : " and ") + o.gltf;
  if (!o.vdb.empty()) s += (s.empty() ? "" : " and ") + o.vdb;
  if (s.empty()) s = o.mp4.empty() ? "no files (--format none: the report only)" : o.mp4 + " (the playblast)";
  return s;
}

// The continuity ratio's lines, and how the frames with a stand-in core were written.
void printContinuityRatio(const BakeArgs& o, const BakeContinuity& c) {
  if (c.ratio) {  // the visible surface's largest jump against the characters' own motion
    const ContinuityRatio& r = *c.ratio;
    std::printf("continuity ratio (largest frame-to-frame jump of the visible surface / the characters' own largest "
                "motion, bound %.0f): %s%s\n",
                kMaxContinuityRatio, r.describe().c_str(), c.ratioOverAtoD ? " (A..D)" : " (the range's part of A..D)");
    std::printf("continuity ratio: the largest jumps:");
    for (const auto& [frame, jump] : c.largestJumps)
      std::printf(" frame %d %.2fx,", frame, r.motion.hausdorff > 0.0 ? jump / r.motion.hausdorff : 0.0);
    const MorphMarkers& m = c.markers;
    std::printf(" (stages: collapse %d..%d, morph %d..%d, expansion %d..%d)\n", m.a, m.b, m.b, m.c, m.c, m.d);
  }
  if (c.coreFrames > 0)
    std::printf(o.keepInnerShell ? "note: %d collapse / expansion frames carry the stand-in core as a second closed "
                                   "shell inside the mesh (--keep-inner-shell)\n"
                                 : "note: %d collapse / expansion frames written as their visible surface: the "
                                   "stand-in core inside the mesh cut away (--keep-inner-shell keeps both shells)\n",
                c.coreFrames);
}

// A morph's summary line and its continuity report.
void printMorphReport(const BakeArgs& o, const BakeReport& r) {
  const auto& n = r.stageFrames;
  std::printf("baked frames %d..%d (%d source, %d collapse, %d morph, %d expand, %d target) at %d^3 into %s in %.2f s\n",
              r.first, r.last, n[0], n[1], n[2], n[3], n[4], o.res, into(o).c_str(), r.frameSeconds);
  if (!r.continuity) return;
  const BakeContinuity& c = *r.continuity;
  std::printf("continuity: %zu frame%s empty or changing volume by more than %.0f%% from the frame before\n",
              c.defects.size(), c.defects.size() == 1 ? "" : "s", 100.0 * kMaxFrameVolumeChange);
  for (const ContinuityDefect& d : c.defects) std::printf("  frame %d: %s\n", d.frame, d.reason.c_str());
  // the largest change, over the range and within B..C (the implicit stage, seams left out)
  std::printf("continuity: %s, largest frame-to-frame volume change %.1f%% at frame %d", c.method.c_str(),
              100.0 * c.largestChange, c.largestChangeFrame);
  if (c.largestChangeInsideFrame >= 0)
    std::printf(", within B..C %.1f%% at frame %d", 100.0 * c.largestChangeInside, c.largestChangeInsideFrame);
  std::printf("\n");
  printContinuityRatio(o, c);
}

// An animorphosis' summary line.
void printAnimorphosisReport(const BakeArgs& o, const Project& p, const BakeReport& r) {
  std::string coherenceNote;
  if (r.coherence)
    coherenceNote = "; temporal coherence (" + std::to_string(r.coherence->toleranceCells).substr(0, 4) + " cell): " +
                    std::to_string(r.coherence->blocksReused) + " of " + std::to_string(r.coherence->blocksEvaluated) +
                    " blocks reused, one " + std::to_string(r.coherence->gridCells[0]) + "x" +
                    std::to_string(r.coherence->gridCells[1]) + "x" + std::to_string(r.coherence->gridCells[2]) +
                    " grid";
  std::printf("baked the animorphosis %s -> %s, frames %d..%d (%zu nodes, %zu triangles in all) at %d^3 into %s in %.2f s%s\n",
              p.animorphosis.sourceActorId.c_str(), p.animorphosis.targetActorId.c_str(), r.first, r.last,
              r.animorphosisNodes, r.triangles, o.res, into(o).c_str(), r.frameSeconds, coherenceNote.c_str());
}

// What went into the VDB folder and the glTF.
void printOutputs(const BakeArgs& o, const std::string& prefix, const Project& p, const BakeReport& r) {
  if (!o.vdb.empty()) {
    std::printf("wrote %d OpenVDB level sets into %s (%s_####.vdb)", r.levelSets, o.vdb.c_str(), prefix.c_str());
    if (r.framesWithoutField > 0)
      std::printf("; %d frames are skinned meshes without an implicit field: no .vdb for them", r.framesWithoutField);
    std::printf("\n");
  }
  if (!o.gltf.empty())
    std::printf("wrote %s: %d frames, %d distinct meshes, %.1f MB at %g fps in %.2f s\n", o.gltf.c_str(), r.frames,
                r.gltfMeshes, r.gltfMegabytes, p.timeline.fps, r.gltfSeconds);
}

int runBake(const std::vector<std::string>& args) {
  BakeArgs o;
  if (std::string e = readArgs(args, o); !e.empty()) return cli::fail("bake", e, 2);
  if (std::string e = checkArgs(o); !e.empty()) return cli::fail("bake", e, 2);
  auto p = loadProject(o.project);
  if (!p) return cli::fail("bake", p.error());
  cli::applyMorphMethodOptions(o.methods, p->morph);
  const std::string prefix = o.name.empty() ? framePrefix(p->name) : o.name;
  if (std::string e = makeFolders(o); !e.empty()) return cli::fail("bake", e);
  const bool animorphosis = !p->morph.enabled() && p->animorphosis.enabled();
  if (animorphosis && o.gpu) return cli::fail("bake", "--gpu: an animorphosis is baked on the CPU (run without --gpu)", 2);
  auto frames = ProjectFrames::prepare(*p, fs::absolute(fs::path(o.project)).parent_path().string());
  if (!frames) return cli::fail("bake", o.project + ": " + frames.error());
  for (const auto& n : frames->notes()) std::printf("note: %s\n", n.c_str());
  BakeSettings settings = bakeSettings(o, prefix);
  std::unique_ptr<cli::GpuImplicitStage> gpuStage;  // --gpu: no device is an error, no fallback
  if (o.gpu) {
    auto g = cli::GpuImplicitStage::create();
    if (!g) return cli::fail("bake", "--gpu: " + g.error());
    gpuStage = std::move(*g);
    settings.implicitStage = gpuStage->polygonizer();
    std::printf("B->C polygonised on the GPU: %s\n", gpuStage->deviceName().c_str());
  }
  ProgressBar bar("baking", o.last - o.first + 1);
  settings.frameDone = [&](int) { bar.step(); };
  JobProgress progress;
  auto r = bakeProject(*frames, settings, progress);
  if (!r) return cli::fail("bake", r.error());
  if (r->animorphosis) printAnimorphosisReport(o, *p, *r);
  else printMorphReport(o, *r);
  printOutputs(o, prefix, *p, *r);
  if (gpuStage && gpuStage->validationErrors() > 0) {
    std::fprintf(stderr, "animorph-cli bake: %u Vulkan validation error(s) in the GPU polygoniser\n",
                 gpuStage->validationErrors());
    return 3;
  }
  PictureOptions pics;
  pics.png = o.png;
  pics.mp4 = o.mp4;
  pics.burnIn = o.burnIn;
  pics.stages = frameStageSpans(*p, o.first, o.last);
  pics.fps = p->timeline.fps;
  pics.width = uint32_t(o.width);
  pics.height = uint32_t(o.height);
  return renderPictures(r->meshes, o.first, o.output, prefix, p->view, pics);
}

}  // namespace

ANIMORPH_CLI_COMMAND("bake", "bake a project's morph into mesh sequences, an animated glTF, VDB level sets (and PNG frames)",
                     "usage: animorph-cli bake PROJECT.animorph --frames A:B --res N -o DIR [--format ply|obj|ply,obj|none]\n"
                     "                         [--obj] [--name NAME] [--gltf FILE.glb] [--vdb DIR] [--png] [--mp4 FILE.mp4 [--size WxH]\n"
                     "                         [--burn-in]] [--gpu] [--jobs J] [--coherence C] [--method M [--correspondence-blend B]]\n"
                     "                         [--keep-inner-shell] [--no-color]\n"
                     "  Bakes every frame A..B: the source's skinned mesh before marker A, its\n"
                     "  collapse onto the stand-in A->B, the polygonised implicit morph B->C (N cells\n"
                     "  along the longest side), the target's expansion C->D and its skinned mesh\n"
                     "  after D; world space, unit normals. A project whose only transformation is an\n"
                     "  animorphosis of two BlobTrees bakes its C(t) instead (CPU, in the trees' own space).\n"
                     "  --format F   the mesh sequence written into DIR, one file per frame named\n"
                     "               NAME_####.ply / NAME_####.obj (frame number padded to 4 digits):\n"
                     "               ply (binary PLY, the default), obj (Wavefront OBJ with vn normals,\n"
                     "               f a//a b//b c//c faces, v x y z r g b when the frame has vertex\n"
                     "               colours), ply,obj (both) or none (no sequence; -o not needed then;\n"
                     "               with no --gltf/--vdb/--png/--mp4 either, nothing is written: the\n"
                     "               bake runs for its report, timing and continuity)\n"
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
                     "  --no-color   an animorphosis' frames without vertex colours (by default they\n"
                     "               carry the primitives' colours: PLY/OBJ vertex colours, glTF\n"
                     "               COLOR_0); saves the colour pass\n"
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
