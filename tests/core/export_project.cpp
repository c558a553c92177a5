// The background-job type (progress, time left, cancel) and the export it runs for File > Export...
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <thread>

#include "core/export/export_project.h"
#include "core/export/frame_files.h"
#include "core/project/project_io.h"
#include "core/io/gltf_import.h"
#include "util/animorph_fixtures.h"
#include "core/util/background_job.h"
#include "util/temp_dir.h"

using namespace animorph;
using namespace animorph::test;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

Project animorphosisProject() { return walkerToFlyerProject("morph me"); }

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) out.push_back(it->path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("background job: runs off the calling thread, reports progress and the time left, and is cancelled",
          "[job]") {
  std::thread::id worker;
  BackgroundJob done("count", [&](JobProgress& pr) -> Status {
    worker = std::this_thread::get_id();
    pr.setTotal(4);
    for (int i = 0; i < 4; ++i) pr.advance();
    return Status::success();
  });
  done.wait();
  CHECK(done.finished());
  CHECK(done.status().ok());
  CHECK_FALSE(done.wasCancelled());
  CHECK(worker != std::this_thread::get_id());
  CHECK(done.progress().fraction() == Approx(1.0));
  CHECK(done.progress().secondsLeft() == Approx(0.0));

  // A job that waits for its cancel: the UI thread sees it running, halfway, then cancels it.
  std::atomic<bool> halfway{false};
  BackgroundJob slow("slow", [&](JobProgress& pr) -> Status {
    pr.setTotal(10);
    pr.setDone(5);
    pr.setStage("halfway");
    halfway = true;
    while (!pr.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return jobCancelled();
  });
  while (!halfway) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK_FALSE(slow.finished());
  CHECK(slow.progress().fraction() == Approx(0.5));
  CHECK(slow.progress().stage() == "halfway");
  // Half done after t seconds: about t seconds left.
  const double left = slow.progress().secondsLeft(), elapsed = slow.progress().elapsedSec();
  CHECK(left > 0.0);
  CHECK(left <= elapsed * 1.01 + 0.01);
  slow.cancel();
  slow.wait();
  CHECK(slow.wasCancelled());

  // An exception in the work is the job's error, naming the job.
  BackgroundJob thrower("Open", [](JobProgress&) -> Status { throw std::runtime_error("out of memory"); });
  thrower.wait();
  REQUIRE_FALSE(thrower.status().ok());
  CHECK_THAT(thrower.status().error(), Contains("Open") && Contains("out of memory"));
  CHECK_FALSE(thrower.wasCancelled());

  CHECK(formatTimeLeft(-1.0).empty());
  CHECK(formatTimeLeft(4.2) == "5 s");
  CHECK(formatTimeLeft(65.0) == "1 min 05 s");
}

TEST_CASE("export settings: saved in the project and read back, bad fields named", "[export]") {
  Project p = animorphosisProject();
  p.exportSettings.format = ExportFormat::ObjSequence;
  p.exportSettings.useTimeline = false;
  p.exportSettings.first = 30;
  p.exportSettings.last = 40;
  p.exportSettings.resolution = 80;
  p.exportSettings.output = "out/frames";
  auto back = projectFromJson(projectToJson(p), "p.animorph");
  REQUIRE(back.ok());
  CHECK(back->exportSettings == p.exportSettings);
  // A project that never exported writes no "export" section.
  CHECK(projectToJson(Project{}).find("\"export\"") == std::string::npos);

  std::string text = projectToJson(p);
  std::string bad = text;
  bad.replace(bad.find("\"obj\""), 5, "\"fbx\"");
  auto refused = projectFromJson(bad, "p.animorph");
  REQUIRE_FALSE(refused.ok());
  CHECK_THAT(refused.error(), Contains("p.animorph: export.format"));
  bad = text;
  const std::string res = "\"resolution\": 80";
  REQUIRE(bad.find(res) != std::string::npos);
  bad.replace(bad.find(res), res.size(), "\"resolution\": 1");
  refused = projectFromJson(bad, "p.animorph");
  REQUIRE_FALSE(refused.ok());
  CHECK_THAT(refused.error(), Contains("export.resolution"));
}

TEST_CASE("export: a PLY sequence of an animorphosis appears whole, a cancelled one leaves no file", "[export]") {
  TempDir tmp;
  Project p = animorphosisProject();
  ExportSettings s;
  s.format = ExportFormat::PlySequence;
  s.useTimeline = false;
  s.first = 30;
  s.last = 33;
  s.resolution = 24;
  s.output = "seq";  // relative: in the project's folder
  JobProgress progress;
  auto r = exportProject(p, tmp.path().string(), s, progress);
  INFO(r.error());
  REQUIRE(r.ok());
  CHECK(r->frames == 4);
  CHECK(progress.fraction() == Approx(1.0));
  CHECK(filesIn(tmp.path() / "seq") ==
        std::vector<std::string>{"morph_me_0030.ply", "morph_me_0031.ply", "morph_me_0032.ply", "morph_me_0033.ply"});
  std::ifstream ply(frameFileName((tmp.path() / "seq").string(), "morph_me", 31, "ply"), std::ios::binary);
  std::string header((std::istreambuf_iterator<char>(ply)), std::istreambuf_iterator<char>());
  CHECK(header.rfind("ply\n", 0) == 0);
  CHECK(r->triangles > 400);

  // Cancelled after the second frame: nothing new in the folder, and no temporary left. The range
  // is long (about two seconds of work) so that the cancel arrives before the export ends even
  // when this thread is descheduled for a while on a loaded machine.
  s.output = (tmp.path() / "cancelled").string();
  s.format = ExportFormat::ObjSequence;
  s.last = 230;
  BackgroundJob job("Export", [&](JobProgress& pr) -> Status {
    auto res = exportProject(p, tmp.path().string(), s, pr);
    return res ? Status::success() : Status(Error{res.error()});
  });
  while (job.progress().done() < 2.0 && !job.finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  job.cancel();
  job.wait();
  CHECK(job.wasCancelled());
  CHECK(filesIn(tmp.path() / "cancelled").empty());
}

TEST_CASE("export: the animated glTF of an animorphosis has a node per frame, errors name the reason", "[export]") {
  TempDir tmp;
  Project p = animorphosisProject();
  p.timeline.frameStart = 40;
  p.timeline.frameEnd = 42;
  ExportSettings s;  // glTF over the timeline's range
  s.resolution = 20;
  s.output = tmp.file("out/morph.glb");
  JobProgress progress;
  auto r = exportProject(p, tmp.path().string(), s, progress);
  INFO(r.error());
  REQUIRE(r.ok());
  REQUIRE(r->files == std::vector<std::string>{s.output});
  auto c = importGltf(s.output);
  INFO(c.error());
  REQUIRE(c.ok());
  int frameNodes = 0;
  for (const auto& n : c->nodes) frameNodes += n.name.rfind("morph_me_00", 0) == 0;
  CHECK(frameNodes == 3);

  s.output.clear();
  auto noPath = exportProject(p, tmp.path().string(), s, progress);
  REQUIRE_FALSE(noPath.ok());
  CHECK_THAT(noPath.error(), Contains("no output path"));
  auto nothing = exportProject(Project{}, tmp.path().string(), ExportSettings{ExportFormat::GltfAnimated, true, 0, 1, 8, "x.glb"}, progress);
  REQUIRE_FALSE(nothing.ok());
  CHECK_THAT(nothing.error(), Contains("no morph or animorphosis"));
}
