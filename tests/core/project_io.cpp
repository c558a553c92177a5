#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sys/stat.h>

#include "core/util/atomic_file.h"
#include "core/doc/document.h"
#include "core/project/project_io.h"
#include "util/temp_dir.h"

using namespace animorph;
using animorph::test::TempDir;

namespace {
Project sample() {
  Project p;
  p.name = "round trip";
  p.timeline.fps = 30.0;
  p.timeline.frameStart = 5;
  p.timeline.frameEnd = 120;
  p.timeline.currentFrame = 17;
  p.view.wireframe = true;
  Actor a;
  a.id = "walker";
  a.name = "Walker";
  a.assetPath = "chars/walker.glb";
  a.clip = 1;
  a.timeOffsetSec = 0.5;
  a.speed = 1.25;
  a.loop = false;
  a.transform.translation = {1.0f, 2.0f, 3.0f};
  a.transform.rotation = glm::normalize(glm::quat(0.9f, 0.1f, 0.3f, 0.0f));
  a.transform.scale = {2.0f, 2.0f, 2.0f};
  p.actors.push_back(a);
  return p;
}
}  // namespace

TEST_CASE("project JSON round trip keeps every field", "[io][project]") {
  Project p = sample();
  auto back = projectFromJson(projectToJson(p), "mem");
  REQUIRE(back.ok());
  CHECK(back->name == p.name);
  CHECK(back->timeline == p.timeline);
  CHECK(back->view == p.view);
  REQUIRE(back->actors.size() == 1);
  const Actor& a = back->actors[0];
  CHECK(a.id == "walker");
  CHECK(a.assetPath == "chars/walker.glb");
  CHECK(a.speed == 1.25);
  CHECK_FALSE(a.loop);
  CHECK(glm::length(a.transform.translation - p.actors[0].transform.translation) < 1e-6f);
  CHECK(std::abs(glm::dot(a.transform.rotation, p.actors[0].transform.rotation)) > 0.99999f);
}

TEST_CASE("a project whose actor rotation is not a unit quaternion reloads unchanged once saved", "[io][project]") {
  // Found by fuzz_project (tests/fuzz/regressions/project/actor_rotation_not_unit.animorph):
  // normalising the saved, already unit quaternion again moved it by an ulp.
  const std::string text = R"({"format": "animorph", "version": 1, "actors": [{"id": "a", "asset": "a.glb",
                               "rotation": [1.0, 0.0, 0.0, 1.0]}]})";
  auto first = projectFromJson(text, "r.animorph");
  REQUIRE(first);
  CHECK(glm::length(first->actors[0].transform.rotation) == Approx(1.0f));
  auto again = projectFromJson(projectToJson(*first), "r.animorph");
  REQUIRE(again);
  CHECK(*again == *first);
}

TEST_CASE("a newer project version is refused with a clear message", "[io][project]") {
  auto r = projectFromJson(R"({"format":"animorph","version":99})", "future.animorph");
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.error(), Catch::Contains("future.animorph") && Catch::Contains("version 99") &&
                            Catch::Contains("newer"));
}

TEST_CASE("bad project files name the file, the element and the reason", "[io][project]") {
  CHECK_THAT(projectFromJson("{", "a.animorph").error(), Catch::Contains("a.animorph: not valid JSON"));
  CHECK_THAT(projectFromJson(R"({"version":1})", "b.animorph").error(), Catch::Contains("not an Animorph project"));
  auto r = projectFromJson(
      R"({"format":"animorph","version":1,"actors":[{"id":"x","asset":"x.glb"},{"id":"y","asset":"y.glb","speed":"fast"}]})",
      "c.animorph");
  CHECK_THAT(r.error(), Catch::Contains("c.animorph: actors[1].speed: expected a number"));
  r = projectFromJson(R"({"format":"animorph","version":1,"actors":[{"id":"x","asset":"x.glb"},{"id":"x","asset":"y.glb"}]})",
                      "d.animorph");
  CHECK_THAT(r.error(), Catch::Contains("actors[1].id: duplicate id 'x'"));
  r = projectFromJson(R"({"format":"animorph","version":1,"actors":[{"id":"x"}]})", "e.animorph");
  CHECK_THAT(r.error(), Catch::Contains("actors[0].asset: missing"));
  r = projectFromJson(R"({"format":"animorph","version":1,"timeline":{"fps":0}})", "f.animorph");
  CHECK_THAT(r.error(), Catch::Contains("timeline.fps"));
}

TEST_CASE("atomic save replaces the file, a failing save leaves the old one intact", "[io][project]") {
  TempDir dir;
  std::string path = dir.file("p.animorph");
  REQUIRE(saveProject(sample(), path).ok());
  auto loaded = loadProject(path);
  REQUIRE(loaded.ok());
  CHECK(loaded->timeline.fps == 30.0);
  std::string before = *readFile(path);

  // Make the directory read-only: creating the temporary fails, the old file stays.
  if (::geteuid() != 0) {
    std::filesystem::permissions(dir.path(), std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    Project changed = sample();
    changed.name = "changed";
    CHECK_FALSE(saveProject(changed, path).ok());
    std::filesystem::permissions(dir.path(), std::filesystem::perms::owner_all);
  }
  // Root ignores directory permissions: make the rename fail instead, by
  // putting a directory where the temporary target's destination is.
  std::string blocked = dir.file("blocked.animorph");
  std::filesystem::create_directory(blocked);
  std::filesystem::create_directory(blocked + "/keep");  // non-empty: rename over it fails
  Status st = saveProject(sample(), blocked);
  CHECK_FALSE(st.ok());
  CHECK_THAT(st.error(), Catch::Contains("blocked.animorph"));
  CHECK(std::filesystem::is_directory(blocked + "/keep"));
  CHECK(*readFile(path) == before);
  // No temporaries are left behind.
  int count = 0;
  for (auto& e : std::filesystem::directory_iterator(dir.path())) {
    (void)e;
    ++count;
  }
  CHECK(count == 2);
}

TEST_CASE("save as re-bases relative asset paths, autosave and recovery", "[io][project]") {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "a");
  std::filesystem::create_directories(dir.path() / "b");
  REQUIRE(saveProject(sample(), dir.file("a/p.animorph")).ok());
  auto doc = Document::open(dir.file("a/p.animorph"));
  REQUIRE(doc.ok());
  Document& d = **doc;
  CHECK(d.resolveAsset("chars/walker.glb") == dir.file("a/chars/walker.glb"));
  REQUIRE(d.saveAs(dir.file("b/q.animorph")).ok());
  CHECK(d.project().actors[0].assetPath == "../a/chars/walker.glb");

  // Autosave writes only when there are unsaved changes and the interval passed.
  CHECK_FALSE(d.autosaveIfDue(0.0));
  d.execute(setActorField(d.project(), "walker", &Actor::speed, 3.0, "speed"));
  CHECK_FALSE(d.autosaveIfDue(30.0));
  CHECK(d.autosaveIfDue(61.0));
  CHECK(std::filesystem::exists(d.autosavePath()));
  CHECK(Document::hasNewerAutosave(d.path()));
  auto rec = Document::recoverAutosave(d.path());
  REQUIRE(rec.ok());
  CHECK((*rec)->project().actors[0].speed == 3.0);
  CHECK((*rec)->dirty());
  CHECK((*rec)->path() == d.path());
  // Saving removes the autosave.
  REQUIRE(d.save().ok());
  CHECK_FALSE(std::filesystem::exists(d.autosavePath()));
  CHECK_FALSE(Document::hasNewerAutosave(d.path()));
}

TEST_CASE("autosave: a few seconds after the first unsaved edit, then at most once an interval", "[io][project]") {
  TempDir dir;
  REQUIRE(saveProject(sample(), dir.file("p.animorph")).ok());
  auto doc = Document::open(dir.file("p.animorph"));
  REQUIRE(doc.ok());
  Document& d = **doc;
  CHECK_FALSE(d.autosaveIfDue(0.0));  // clean: nothing to write however long it waits
  CHECK_FALSE(d.autosaveIfDue(100.0));

  // An edit after a long idle time is not held back by the interval: 5 s after it is seen.
  d.execute(setActorField(d.project(), "walker", &Actor::speed, 2.0, "speed"));
  CHECK_FALSE(d.autosaveIfDue(100.5));
  CHECK_FALSE(d.autosaveIfDue(105.4));
  CHECK(d.autosaveIfDue(105.6));
  CHECK_FALSE(std::filesystem::exists(dir.file("p.animorph") + ".tmp"));
  auto rec = Document::recoverAutosave(d.path());
  REQUIRE(rec.ok());
  CHECK((*rec)->project().actors[0].speed == 2.0);

  // Editing on: at most once an interval after that.
  d.execute(setActorField(d.project(), "walker", &Actor::speed, 3.0, "speed"));
  CHECK_FALSE(d.autosaveIfDue(111.0));
  CHECK_FALSE(d.autosaveIfDue(165.5));
  CHECK(d.autosaveIfDue(165.7));
  CHECK_FALSE(d.autosaveIfDue(200.0));  // nothing new since

  // After a save the next edit gets its first autosave soon again; interval 0 writes at once.
  REQUIRE(d.save().ok());
  d.execute(setActorField(d.project(), "walker", &Actor::speed, 4.0, "speed"));
  CHECK_FALSE(d.autosaveIfDue(201.0));
  CHECK(d.autosaveIfDue(206.1));
  d.execute(setActorField(d.project(), "walker", &Actor::speed, 5.0, "speed"));
  CHECK(d.autosaveIfDue(206.2, 0.0));
}
