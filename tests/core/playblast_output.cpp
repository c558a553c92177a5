// What a playblast is made of besides the pictures: the stage labels burnt in per frame, the
// ffmpeg pipe that writes the .mp4 under a temporary name (read back with ffprobe), and the
// settings saved in the project.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/export/frame_stage.h"
#include "core/project/project_io.h"
#include "core/export/mp4_writer.h"
#include "util/animorph_fixtures.h"
#include "util/temp_dir.h"
#include "util/test_skip.h"

using namespace animorph;
using namespace animorph::test;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A project with a morph between two actors (markers 10, 20, 30, 40); sourceKind: the source's kind.
Project morphProject(ActorKind sourceKind) {
  Project p;
  Actor a, b;
  a.id = "src";
  a.kind = sourceKind;
  b.id = "dst";
  p.actors = {a, b};
  p.morph.sourceActorId = "src";
  p.morph.targetActorId = "dst";
  p.morph.markers = {10, 20, 30, 40};
  return p;
}

bool haveFfmpeg() { return std::system("ffmpeg -version >/dev/null 2>&1 && ffprobe -version >/dev/null 2>&1") == 0; }

// "width,height,frames" of the first video stream, as ffprobe counts them.
std::string probe(const std::string& mp4) {
  const std::string cmd = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                          "stream=width,height,nb_read_frames -of csv=p=0 '" + mp4 + "'";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {};
  char buf[128] = {};
  const size_t n = std::fread(buf, 1, sizeof buf - 1, p);
  pclose(p);
  std::string s(buf, n);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

std::vector<uint8_t> gradient(uint32_t w, uint32_t h, int k) {
  std::vector<uint8_t> px(size_t(w) * h * 4);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      uint8_t* q = &px[(size_t(y) * w + x) * 4];
      q[0] = uint8_t(x * 4 + k * 20), q[1] = uint8_t(y * 4), q[2] = 128, q[3] = 255;
    }
  return px;
}

// A 64x48 mp4 named name in dir, frames as gradient(64, 48, k).
Mp4Options smallMp4(const TempDir& dir, const std::string& name) {
  Mp4Options o;
  o.path = dir.file(name);
  o.width = 64;
  o.height = 48;
  return o;
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("playblast stages: a morph's frames fall into before A, A..B, B..C, C..D and after D", "[playblast]") {
  const Project p = morphProject(ActorKind::Gltf);
  const auto spans = frameStageSpans(p, 0, 50);
  REQUIRE(spans.size() == 5);
  const std::vector<std::tuple<int, int, std::string>> want = {
      {0, 9, "before A"}, {10, 19, "A..B"}, {20, 30, "B..C"}, {31, 40, "C..D"}, {41, 50, "after D"}};
  for (size_t i = 0; i < spans.size(); ++i) {
    CHECK(spans[i].first == std::get<0>(want[i]));
    CHECK(spans[i].last == std::get<1>(want[i]));
    CHECK(spans[i].label == std::get<2>(want[i]));
  }
  CHECK(frameStageLabel(p, 25) == "B..C");
  // A range inside one stage is one span.
  CHECK(frameStageSpans(p, 22, 28).size() == 1);
  // A BlobTree source has no collapse: the bake moves A onto B.
  const auto tree = frameStageSpans(morphProject(ActorKind::BlobTree), 0, 50);
  REQUIRE(tree.size() == 4);
  CHECK(tree[0].label == "before A");
  CHECK(tree[0].last == 19);
  // An animorphosis is one stage; a project with nothing to bake has none.
  const auto anim = frameStageSpans(walkerToFlyerProject("w", 0, 12), 0, 12);
  REQUIRE(anim.size() == 1);
  CHECK(anim[0].label == "animorphosis");
  CHECK(frameStageLabel(Project{}, 3).empty());
}

TEST_CASE("playblast burn-in: one drawtext per stage, enabled on its frames, numbered from the first frame",
          "[playblast]") {
  Mp4Options o;
  o.firstFrame = 10;
  CHECK(mp4BurnInFilter(o).empty());  // no burn-in asked
  o.burnIn = true;
  CHECK_THAT(mp4BurnInFilter(o), Contains("n+10"));
  o.stages = frameStageSpans(morphProject(ActorKind::Gltf), 10, 25);
  const std::string f = mp4BurnInFilter(o);
  CHECK_THAT(f, Contains("A..B':enable='between(n\\,0\\,9)'"));
  CHECK_THAT(f, Contains("B..C':enable='between(n\\,10\\,15)'"));
  size_t filters = 0;
  for (size_t at = f.find("drawtext="); at != std::string::npos; at = f.find("drawtext=", at + 1)) ++filters;
  CHECK(filters == 2);
}

TEST_CASE("Mp4Writer: frames piped to ffmpeg become an mp4 of that size and count, renamed into place",
          "[playblast]") {
  if (!haveFfmpeg()) {
    ANIMORPH_SKIP("ffmpeg or ffprobe not installed (run.sh installs them): the mp4 is not checked");
  }
  TempDir dir;
  Mp4Options o = smallMp4(dir, "blast.mp4");
  o.fps = 24.0;
  o.burnIn = true;
  o.firstFrame = 18;
  o.stages = frameStageSpans(morphProject(ActorKind::Gltf), 18, 23);
  auto w = Mp4Writer::start(o);
  REQUIRE(w);
  for (int k = 0; k < 6; ++k) REQUIRE((*w)->addFrame(gradient(64, 48, k)));
  CHECK_FALSE(fs::exists(o.path));  // not before finish (ffmpeg writes the temporary when it likes)
  Status st = (*w)->finish();
  INFO(st.error());
  REQUIRE(st);
  CHECK(probe(o.path) == "64,48,6");
  CHECK(filesIn(dir.path()) == std::vector<std::string>{"blast.mp4"});
  // A frame of the wrong size is refused, naming the file.
  auto w2 = Mp4Writer::start(o);
  REQUIRE(w2);
  Status bad = (*w2)->addFrame(gradient(32, 48, 0));
  REQUIRE_FALSE(bad);
  CHECK_THAT(bad.error(), Contains(o.path));
}

TEST_CASE("Mp4Writer: a writer dropped before finish (a cancelled playblast) leaves no file", "[playblast]") {
  if (!haveFfmpeg()) {
    ANIMORPH_SKIP("ffmpeg not installed: not checked");
  }
  TempDir dir;
  Mp4Options o = smallMp4(dir, "cancelled.mp4");
  {
    auto w = Mp4Writer::start(o);
    REQUIRE(w);
    for (int k = 0; k < 3; ++k) REQUIRE((*w)->addFrame(gradient(64, 48, k)));
  }
  CHECK(filesIn(dir.path()).empty());
  // Sizes H.264 cannot take are refused before ffmpeg starts.
  o.width = 65;
  auto odd = Mp4Writer::start(o);
  REQUIRE_FALSE(odd);
  CHECK_THAT(odd.error(), Contains("cancelled.mp4") && Contains("even"));
}

TEST_CASE("playblast settings: saved in the project file, read back, bad fields named", "[playblast]") {
  Project p = walkerToFlyerProject("w", 0, 12);
  p.playblastSettings.useTimeline = false;
  p.playblastSettings.first = 3;
  p.playblastSettings.last = 9;
  p.playblastSettings.width = 640;
  p.playblastSettings.height = 360;
  p.playblastSettings.burnIn = false;
  p.playblastSettings.viewportCamera = false;
  p.playblastSettings.output = "out/w.mp4";
  auto back = projectFromJson(projectToJson(p), "w.animorph");
  REQUIRE(back);
  CHECK(back->playblastSettings == p.playblastSettings);
  // Left out of the file until set.
  CHECK(projectToJson(walkerToFlyerProject("w", 0, 12)).find("playblast") == std::string::npos);
  std::string text = projectToJson(p);
  const std::string w = "\"width\": 640";
  REQUIRE(text.find(w) != std::string::npos);
  text.replace(text.find(w), w.size(), "\"width\": 641");
  auto odd = projectFromJson(text, "w.animorph");
  REQUIRE_FALSE(odd);
  CHECK_THAT(odd.error(), Contains("w.animorph: playblast.width") && Contains("even"));
}
