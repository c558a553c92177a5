// The one bake route (export/bake_route.h) that animorph-cli bake, File > Export..., the playblast
// and the farm's chunks take: files the same for any number of parallel frames, staged (nothing
// left by a failing or cancelled bake), the plugged-in polygoniser of the morph's B->C stage, the
// report's stages, continuity (the continuity ratio too) and coherence, collapse and expansion frames
// as their visible surface unless keepInnerShell, bad settings named.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <thread>

#include "core/animorphosis/evaluate_generic.h"
#include "core/export/bake_route.h"
#include "core/export/export_project.h"
#include "core/export/frame_files.h"
#include "core/project/animorphosis_project.h"
#include "core/scene/visible_surface.h"
#include "core/util/background_job.h"
#include "util/animorph_fixtures.h"
#include "util/morph_fixtures.h"
#include "util/temp_dir.h"

using namespace animorph;
using namespace animorph::test;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// Every file under dir (recursively) and its bytes, by the path relative to dir.
std::map<std::string, std::string> filesUnder(const fs::path& dir) {
  std::map<std::string, std::string> out;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file()) continue;
    std::ifstream in(it->path(), std::ios::binary);
    std::string bytes(std::istreambuf_iterator<char>(in), {});
    // OpenVDB writes a random UUID into every file's header (36 characters from byte 21): masked.
    if (it->path().extension() == ".vdb" && bytes.size() > 57) bytes.replace(21, 36, 36, '-');
    out[fs::relative(it->path(), dir).string()] = std::move(bytes);
  }
  return out;
}

const ProjectFrames& walkerToFlyerFrames() {
  static const ProjectFrames frames = ProjectFrames::prepare(walkerToFlyerProject("walker"), ".").value();
  return frames;
}

const ProjectFrames& demoMorphFrames() {
  static const ProjectFrames frames = ProjectFrames::prepare(demoMorph().project, demoMorph().dir).value();
  return frames;
}

BakeSettings everyOutput(const fs::path& dir, int first, int last, int res) {
  BakeSettings s;
  s.first = first;
  s.last = last;
  s.resolution = res;
  s.outputs.prefix = "m";
  s.outputs.dir = (dir / "seq").string();
  s.outputs.ply = s.outputs.obj = true;
  s.outputs.gltf = (dir / "m.glb").string();
  s.outputs.vdbDir = (dir / "vdb").string();
  return s;
}

}  // namespace

TEST_CASE("bake route: the same files for any number of parallel frames, every output staged and renamed",
          "[bake][export]") {
  std::mt19937 rng(20261129);
  const MorphMarkers& mk = demoMorph().runtime->setup.markers;
  struct Case {
    const ProjectFrames* frames;
    int first, last;
  };
  // Random ranges (seeded) of the animorphosis and of the demo morph across its stages' seams.
  std::vector<Case> cases;
  for (int i = 0; i < 2; ++i) {
    const int a = std::uniform_int_distribution<int>(20, 70)(rng);
    cases.push_back({&walkerToFlyerFrames(), a, a + std::uniform_int_distribution<int>(2, 5)(rng)});
  }
  for (int seam : {mk.a, mk.b, mk.c, mk.d}) {
    const int a = seam - std::uniform_int_distribution<int>(1, 2)(rng);
    cases.push_back({&demoMorphFrames(), a, a + 3});
  }
  for (const Case& c : cases) {
    INFO("frames " << c.first << ".." << c.last << (c.frames->morph() ? " of the demo morph" : " of the animorphosis"));
    std::map<std::string, std::string> first;
    for (int jobs : {1, 3}) {
      TempDir tmp;
      BakeSettings s = everyOutput(tmp.path(), c.first, c.last, 16);
      s.jobs = jobs;
      bool field = false;  // level sets only where the range has a field (else the bake refuses --vdb)
      for (int f = c.first; f <= c.last; ++f) field = field || c.frames->stageAt(f) == MorphStage::Morph;
      if (!field) s.outputs.vdbDir.clear();
      JobProgress progress;
      auto r = bakeProject(*c.frames, s, progress);
      INFO("jobs " << jobs << ": " << r.error());
      REQUIRE(r.ok());
      CHECK(progress.done() == Approx(c.last - c.first + 1));
      auto files = filesUnder(tmp.path());
      for (const auto& [name, bytes] : files) CHECK(name.find(".part-") == std::string::npos);
      CHECK(files.size() == r->files.size());
      CHECK(files.count("m.glb") == 1);
      CHECK(files.count("seq/m_" + std::to_string(10000 + c.last).substr(1) + ".obj") == 1);
      if (jobs == 1) first = std::move(files);
      else CHECK((files == first));  // byte for byte
    }
  }
}

TEST_CASE("bake route: a failing or cancelled bake leaves nothing at the outputs", "[bake][export]") {
  TempDir tmp;
  const MorphMarkers& mk = demoMorph().runtime->setup.markers;
  // Frames before B are baked and staged, then the plugged-in B->C polygoniser fails.
  BakeSettings s = everyOutput(tmp.path(), mk.b - 3, mk.b + 2, 16);
  s.jobs = 2;
  s.implicitStage = [](const MorphRuntime&, double, int) -> Result<MorphFrame> {
    return Error{"the device was lost"};
  };
  JobProgress progress;
  auto failed = bakeProject(demoMorphFrames(), s, progress);
  REQUIRE_FALSE(failed.ok());
  REQUIRE(demoMorphFrames().stageAt(mk.b - 1) == MorphStage::Collapse);
  REQUIRE(demoMorphFrames().stageAt(mk.b) == MorphStage::Morph);
  CHECK(failed.error() == "frame " + std::to_string(mk.b) + ": the device was lost");
  CHECK(progress.done() >= 3.0);  // the collapse frames before B were baked
  CHECK(filesUnder(tmp.path()).empty());

  // Every frame baked, then the .glb's place is taken by a folder: named, and no frame file renamed
  // into place either.
  BakeSettings blocked = everyOutput(tmp.path(), 40, 42, 16);
  fs::create_directories(blocked.outputs.gltf);
  auto refused = bakeProject(walkerToFlyerFrames(), blocked, progress);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error() == blocked.outputs.gltf + ": is a folder, cannot put the finished file there");
  CHECK(filesUnder(tmp.path()).empty());
  fs::remove_all(blocked.outputs.gltf);

  // Cancelled once two frames are done, frames baked two at a time.
  BakeSettings c = everyOutput(tmp.path(), 30, 200, 20);
  c.jobs = 2;
  BackgroundJob job("Bake", [&](JobProgress& pr) -> Status {
    auto r = bakeProject(walkerToFlyerFrames(), c, pr);
    return r ? Status::success() : Status(Error{r.error()});
  });
  while (job.progress().done() < 2.0 && !job.finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  job.cancel();
  job.wait();
  CHECK(job.wasCancelled());
  CHECK(filesUnder(tmp.path()).empty());
}

TEST_CASE("bake route: the plugged-in polygoniser bakes exactly the morph's B->C frames", "[bake]") {
  const MorphRuntime& rt = *demoMorph().runtime;
  const MorphMarkers& mk = rt.setup.markers;
  std::mutex mutex;
  std::vector<int> asked;
  BakeSettings s;
  s.first = mk.b - 2;
  s.last = mk.b + 2;
  s.resolution = 16;
  s.jobs = 2;
  s.outputs.keepMeshes = true;
  JobProgress cpuProgress;
  auto cpu = bakeProject(demoMorphFrames(), s, cpuProgress);
  REQUIRE(cpu.ok());
  // The plugged-in polygoniser: the CPU's B->C frame shifted by 1 m along x, so its frames show.
  s.implicitStage = [&](const MorphRuntime& r, double timeSec, int res) -> Result<MorphFrame> {
    {
      std::lock_guard<std::mutex> lock(mutex);
      asked.push_back(int(std::lround(timeSec * r.timeline.fps)));
    }
    MorphFrameSettings fs;
    fs.resolution = res;
    auto fr = evaluateMorphFrame(r, timeSec, fs);
    if (fr)
      for (auto& p : fr->mesh.positions) p.x += 1.0f;
    return fr;
  };
  JobProgress progress;
  auto plugged = bakeProject(demoMorphFrames(), s, progress);
  INFO(plugged.error());
  REQUIRE(plugged.ok());
  std::sort(asked.begin(), asked.end());
  std::vector<int> morphFrames;
  for (int f = s.first; f <= s.last; ++f)
    if (demoMorphFrames().stageAt(f) == MorphStage::Morph) morphFrames.push_back(f);
  CHECK(asked == morphFrames);
  REQUIRE(morphFrames.size() >= 2);
  CHECK(plugged->stageFrames[size_t(MorphStage::Morph)] == int(morphFrames.size()));
  CHECK(plugged->stageFrames == cpu->stageFrames);
  for (int f = s.first; f <= s.last; ++f) {
    INFO("frame " << f);
    const TriangleMesh& a = cpu->meshes[size_t(f - s.first)];
    const TriangleMesh& b = plugged->meshes[size_t(f - s.first)];
    REQUIRE(a.positions.size() == b.positions.size());
    REQUIRE_FALSE(a.positions.empty());
    const float shift = demoMorphFrames().stageAt(f) == MorphStage::Morph ? 1.0f : 0.0f;
    for (size_t i = 0; i < a.positions.size(); i += 97) CHECK(b.positions[i].x == Approx(a.positions[i].x + shift));
  }
}

TEST_CASE("bake route: the report counts stages and triangles, measures continuity, reports coherence", "[bake]") {
  const MorphRuntime& rt = *demoMorph().runtime;
  const MorphMarkers& mk = rt.setup.markers;
  BakeSettings s;
  s.first = mk.b - 3;
  s.last = mk.b + 2;
  s.resolution = 16;
  s.measureContinuity = true;
  s.outputs.keepMeshes = true;
  JobProgress progress;
  auto r = bakeProject(demoMorphFrames(), s, progress);
  INFO(r.error());
  REQUIRE(r.ok());
  CHECK_FALSE(r->animorphosis);
  CHECK(r->frames == s.last - s.first + 1);
  int frames = 0;
  for (int n : r->stageFrames) frames += n;
  CHECK(frames == r->frames);
  CHECK(r->stageFrames[size_t(MorphStage::Collapse)] == 3);
  CHECK(r->stageFrames[size_t(MorphStage::Morph)] == 3);
  size_t triangles = 0;
  for (const auto& m : r->meshes) triangles += m.triangleCount();
  CHECK(r->triangles == triangles);
  REQUIRE(r->continuity);
  CHECK(r->continuity->method == morphMethodName(rt.setup.method));
  REQUIRE(r->continuity->frames.size() == size_t(r->frames));
  for (int k = 0; k < r->frames; ++k) {
    CHECK(r->continuity->frames[size_t(k)].frame == s.first + k);
    CHECK(r->continuity->frames[size_t(k)].volume > 0.0);
  }
  CHECK(r->continuity->defects.size() == continuityDefects(r->continuity->frames).size());
  // The pairs within B..C are (B, B+1) and (B+1, B+2).
  CHECK((r->continuity->largestChangeInsideFrame == mk.b + 1 || r->continuity->largestChangeInsideFrame == mk.b + 2));

  // An animorphosis on one grid with temporal coherence: blocks reused, the grid named.
  BakeSettings a;  // before the interval the walker walks: blocks of its body carry over
  a.first = 0;
  a.last = 6;
  a.resolution = 24;
  a.coherence = 0.1f;
  a.outputs.keepMeshes = true;
  auto c = bakeProject(walkerToFlyerFrames(), a, progress);
  INFO(c.error());
  REQUIRE(c.ok());
  CHECK(c->animorphosis);
  CHECK(c->animorphosisNodes == walkerToFlyerFrames().animorphosis()->size());
  REQUIRE(c->coherence);
  CHECK(c->coherence->blocksReused > 0);
  CHECK(c->coherence->blocksReused < c->coherence->blocksEvaluated);
  CHECK(c->coherence->gridCells[0] > 0);
  CHECK(c->stageFrames[size_t(MorphStage::Morph)] == 7);
  for (const auto& m : c->meshes) CHECK(m.triangleCount() > 100);
}

TEST_CASE("bake route: expansion frames as their visible surface unless keepInnerShell, the continuity ratio measured",
          "[bake][export][continuity]") {
  const MorphRuntime& rt = *demoMorph().runtime;
  const MorphMarkers& mk = rt.setup.markers;
  BakeSettings s;  // the first expansion frames: the stand-in core is still inside the mesh
  s.first = mk.c + 1;
  s.last = mk.c + 3;
  s.resolution = 16;
  s.measureContinuity = true;
  s.outputs.keepMeshes = true;
  JobProgress progress;
  auto visible = bakeProject(demoMorphFrames(), s, progress);
  INFO(visible.error());
  REQUIRE(visible.ok());
  s.keepInnerShell = true;
  auto kept = bakeProject(demoMorphFrames(), s, progress);
  INFO(kept.error());
  REQUIRE(kept.ok());
  for (int f = s.first; f <= s.last; ++f) {
    INFO("frame " << f);
    const size_t k = size_t(f - s.first);
    MorphFrameSettings fs;
    fs.resolution = s.resolution;
    auto fr = evaluateMorphFrame(rt, demoMorph().project.timeline.frameToSec(f), fs);
    REQUIRE(fr.ok());
    REQUIRE(fr->coreTriangles > 0);
    const TriangleMesh seen = visibleSurface(rt, *fr);
    REQUIRE(seen.positions != fr->mesh.positions);  // something was cut, so the two modes differ
    CHECK(visible->meshes[k].positions == seen.positions);
    CHECK(visible->meshes[k].indices == seen.indices);
    CHECK(kept->meshes[k].positions == fr->mesh.positions);
    CHECK(kept->meshes[k].indices == fr->mesh.indices);
    // The volume measured is both shells' union in either mode.
    const double volume = measureFrame(f, fr->mesh, nullptr, fr->coreTriangles).volume;
    CHECK(visible->continuity->frames[k].volume == volume);
    CHECK(kept->continuity->frames[k].volume == volume);
  }
  for (const auto* r : {&*visible, &*kept}) {
    REQUIRE(r->continuity);
    const BakeContinuity& c = *r->continuity;
    CHECK(c.coreFrames == 3);
    REQUIRE(c.ratio);
    CHECK(c.ratio->first == s.first);
    CHECK(c.ratio->last == s.last);
    CHECK_FALSE(c.ratioOverAtoD);  // only the range's part of A..D
    REQUIRE(c.largestJumps.size() == 2);  // the pairs (C+1, C+2) and (C+2, C+3)
    CHECK(c.largestJumps[0].second >= c.largestJumps[1].second);
    CHECK(c.ratio->jump == c.largestJumps[0].second);
    CHECK(c.ratio->jumpFrame == c.largestJumps[0].first);
    CHECK(c.ratio->jump > 0.0);
    CHECK(c.ratio->motion.hausdorff > 0.0);
  }
  // Both modes measure the visible surface: the same jumps whichever shells were written.
  CHECK(visible->continuity->largestJumps == kept->continuity->largestJumps);
}

TEST_CASE("bake route: bad settings are named before anything is baked or written", "[bake]") {
  TempDir tmp;
  JobProgress progress;
  auto refused = [&](BakeSettings s) {
    auto r = bakeProject(walkerToFlyerFrames(), s, progress);
    CHECK(filesUnder(tmp.path()).empty());
    CHECK(progress.done() == 0.0);
    return r.ok() ? std::string("(accepted)") : r.error();
  };
  BakeSettings s = everyOutput(tmp.path() / "out", 40, 42, 16);
  BakeSettings b = s;
  b.first = 43;
  CHECK_THAT(refused(b), Contains("the last frame 42 is before the first 43"));
  b = s;
  b.first = -1;
  CHECK_THAT(refused(b), Contains("frame -1 is negative"));
  b = s;
  b.resolution = 1;
  CHECK_THAT(refused(b), Contains("resolution 1 is outside 2..1024"));
  b = s;
  b.jobs = 0;
  CHECK_THAT(refused(b), Contains("expected 1..256"));
  b = s;
  b.coherence = 0.7f;
  CHECK_THAT(refused(b), Contains("expected 0..0.5"));
  b = s;
  b.outputs.dir.clear();
  CHECK_THAT(refused(b), Contains("no folder chosen"));
  // A folder that cannot be made: named, nothing baked.
  const std::string blocker = tmp.file("a_file");
  { std::ofstream(blocker) << "x"; }
  b = s;
  b.outputs.vdbDir = blocker + "/vdb";
  auto r = bakeProject(walkerToFlyerFrames(), b, progress);
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.error(), Contains(blocker));
  CHECK(progress.done() == 0.0);
}

TEST_CASE("bake route: an animorphosis' frames are compiled straight from C, the snapshot's programs exactly",
          "[bake]") {
  const ProjectFrames& frames = walkerToFlyerFrames();
  REQUIRE(frames.animorphosis());
  const Project p = walkerToFlyerProject("walker");
  const AnimorphosisTiming timing = animorphosisTiming(p);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  FieldEvaluator ev;
  // Before, inside and after the interval (1 s to 3 s at 24 frames a second), out of order.
  for (int f : {60, 0, 30, 24, 48, 72, 96, 31}) {
    INFO("frame " << f);
    const FieldProgram direct = frames.animorphosisProgram(f);
    const FieldProgram ref = compileGeneric(*frames.animorphosis(), timing, p.timeline.frameToSec(f));
    REQUIRE(direct.ops.size() == ref.ops.size());
    REQUIRE(direct.primitiveCount() == ref.primitiveCount());
    CHECK(direct.threshold == ref.threshold);
    CHECK(direct.params == ref.params);
    CHECK(direct.bounds().min == ref.bounds().min);
    CHECK(direct.bounds().max == ref.bounds().max);
    REQUIRE_FALSE(ref.bounds().empty());
    const Bounds box = ref.bounds();
    int inside = 0;
    for (int i = 0; i < 100; ++i) {
      const glm::vec3 q = box.min + (box.max - box.min) * glm::vec3(u(rng), u(rng), u(rng));
      const float a = ev.evaluatePoint(direct, q), b = ev.evaluatePoint(ref, q);
      REQUIRE(a == b);
      inside += a >= 0.0f;
    }
    CHECK(inside > 0);
  }
}
