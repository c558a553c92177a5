#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "core/project/project_io.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;
namespace fs = std::filesystem;

namespace {
void makeDirty(Document& d) {
  d.execute(std::make_unique<SetValueCommand<int>>(
      "Set range end", [](Project& p) { return &p.timeline.frameEnd; }, d.project().timeline.frameEnd, 42));
}

// Saves an empty project as NAME in the fixture's folder, opens it, sets autosave to every 5 s;
// returns its path.
std::string openWithAutosaveEvery5s(EditorFixture& f, const std::string& name) {
  const std::string path = f.dir.file(name);
  REQUIRE(saveProject(Project{}, path).ok());
  f.h.ui->requestOpen(path);
  f.h.frames(1);
  REQUIRE(f.h.doc().path() == path);
  f.h.ui->state().prefs.autosaveIntervalSec = 5.0;
  return path;
}
}  // namespace

TEST_CASE("New with a dirty document asks Save / Don't Save / Cancel", "[unsaved]") {
  EditorFixture f;
  auto& h = f.h;
  makeDirty(h.doc());
  Document* before = &h.doc();
  h.tapKey(GLFW_KEY_N, true);
  CHECK(h.ui->state().unsavedPromptOpen);
  REQUIRE(h.hasWidget("prompt/cancel"));
  h.clickWidget("prompt/cancel");
  h.frames(1);
  CHECK(&h.doc() == before);  // nothing happened
  CHECK(h.doc().dirty());
  CHECK_FALSE(h.hasWidget("prompt/cancel"));

  h.tapKey(GLFW_KEY_N, true);
  h.clickWidget("prompt/dont_save");
  CHECK(&h.doc() != before);
  CHECK_FALSE(h.doc().dirty());
  CHECK(h.doc().project().timeline.frameEnd == 96);

  // A clean document is replaced without asking.
  h.tapKey(GLFW_KEY_N, true);
  CHECK_FALSE(h.ui->state().unsavedPromptOpen);
}

TEST_CASE("Quit with an untitled dirty document: Save goes through Save As, then quits", "[unsaved]") {
  EditorFixture f;
  auto& h = f.h;
  makeDirty(h.doc());
  h.tapKey(GLFW_KEY_Q, true);
  CHECK_FALSE(h.ui->output().quit);
  h.clickWidget("prompt/save");
  h.frames(1);
  REQUIRE(h.ui->state().browser.isOpen());
  CHECK(h.ui->state().browser.mode() == FileBrowser::Mode::Save);
  h.type(f.dir.file("kept"));
  h.tapKey(GLFW_KEY_ENTER);
  CHECK(h.ui->output().quit);
  auto saved = loadProject(f.dir.file("kept.animorph"));
  REQUIRE(saved.ok());
  CHECK(saved->timeline.frameEnd == 42);
}

TEST_CASE("the window's close button goes through the same prompt", "[unsaved]") {
  EditorFixture f;
  auto& h = f.h;
  h.ui->requestQuit();
  h.frames(1);
  CHECK(h.ui->output().quit);  // clean: quits at once

  EditorFixture g;
  makeDirty(g.h.doc());
  g.h.ui->requestQuit();
  g.h.frames(2);
  CHECK_FALSE(g.h.ui->output().quit);
  g.h.clickWidget("prompt/dont_save");
  CHECK(g.h.ui->output().quit);
}

TEST_CASE("opening a project with a newer autosave offers Recover / Discard", "[unsaved]") {
  EditorFixture f;
  auto& h = f.h;
  std::string path = f.dir.file("work.animorph");
  Project saved;
  saved.timeline.frameEnd = 10;
  REQUIRE(saveProject(saved, path).ok());
  Project autosaved = saved;
  autosaved.timeline.frameEnd = 77;
  REQUIRE(saveProject(autosaved, path + ".autosave").ok());
  fs::last_write_time(path + ".autosave", fs::last_write_time(path) + std::chrono::seconds(5));

  h.ui->requestOpen(path);
  h.frames(2);
  REQUIRE(h.hasWidget("prompt/recover"));
  h.clickWidget("prompt/recover");
  CHECK(h.doc().path() == path);
  CHECK(h.doc().project().timeline.frameEnd == 77);
  CHECK(h.doc().dirty());  // recovered work is not saved yet

  // Discard deletes the autosave and opens the file as saved.
  EditorFixture g;
  g.h.ui->requestOpen(path);
  g.h.frames(2);
  g.h.clickWidget("prompt/discard");
  CHECK(g.h.doc().project().timeline.frameEnd == 10);
  CHECK_FALSE(g.h.doc().dirty());
  CHECK_FALSE(fs::exists(path + ".autosave"));
}

TEST_CASE("a bad project shows an error and the editor keeps running", "[unsaved]") {
  EditorFixture f;
  auto& h = f.h;
  std::string path = f.dir.file("broken.animorph");
  std::ofstream(path) << "{ \"format\": \"animorph\", \"version\": 1, \"actors\": [ { \"speed\": \"fast\" } ] }";
  Document* before = &h.doc();
  h.ui->requestOpen(path);
  h.frames(3);  // the open job's error arrives after the first frame; its popup is placed on the third
  CHECK(&h.doc() == before);
  CHECK(h.ui->state().status.error);
  CHECK(h.ui->state().status.text.find("broken.animorph") != std::string::npos);
  REQUIRE(h.hasWidget("error/ok"));
  h.clickWidget("error/ok");
  h.frames(1);
  CHECK_FALSE(h.hasWidget("error/ok"));
  h.tapKey(GLFW_KEY_SPACE);  // still responsive
  CHECK(h.ui->state().playback.playing());
}

TEST_CASE("autosave runs from the frame loop at the preference's interval", "[unsaved]") {
  EditorFixture f;
  auto& h = f.h;
  const std::string path = openWithAutosaveEvery5s(f, "auto.animorph");
  makeDirty(h.doc());
  h.frames(1);
  h.frames(3, 1.0);
  CHECK_FALSE(fs::exists(path + ".autosave"));
  h.frames(3, 1.0);
  CHECK(fs::exists(path + ".autosave"));
  CHECK(loadProject(path + ".autosave")->timeline.frameEnd == 42);
}

TEST_CASE("an autosave does not replace a report shown moments before, and says so once it is old", "[unsaved]") {
  EditorFixture f;
  auto& h = f.h;
  const std::string path = openWithAutosaveEvery5s(f, "report.animorph");
  makeDirty(h.doc());
  h.ui->state().status = {"Baked 12 keys", false};  // a job's report, set as a panel sets it
  h.frames(1);
  h.frames(7, 1.0);
  REQUIRE(fs::exists(path + ".autosave"));  // saved all the same
  CHECK(h.ui->state().status.text == "Baked 12 keys");
  // Later, with the report older than the hold, the next autosave is the status bar's news.
  fs::remove(path + ".autosave");
  h.doc().execute(std::make_unique<SetValueCommand<int>>(
      "Set range end", [](Project& p) { return &p.timeline.frameEnd; }, h.doc().project().timeline.frameEnd, 43));
  h.frames(12, 1.0);
  REQUIRE(fs::exists(path + ".autosave"));
  CHECK(h.ui->state().status.text.rfind("Autosaved to ", 0) == 0);
}

TEST_CASE("opening a glTF starts a new untitled project with the character imported", "[unsaved][open]") {
  EditorFixture f;
  f.loadHeroScene();
  auto& h = f.h;
  std::string asset = f.dir.file("walker.gltf");
  writeTestCharacter(asset);

  // The scene is clean: Open replaces it at once, as a project would.
  h.ui->requestOpen(asset);
  h.frames(2);
  CHECK(h.doc().path().empty());  // untitled: Save asks where
  REQUIRE(h.doc().project().actors.size() == 1);
  CHECK(h.doc().project().actors[0].assetPath == asset);
  CHECK(h.doc().selection.actorId == h.doc().project().actors[0].id);
  CHECK(h.doc().dirty());
  CHECK(h.doc().project().timeline.frameEnd == 24);  // the 1 s clip at 24 fps
  CHECK_FALSE(h.ui->state().status.error);
  CHECK_THAT(h.ui->state().status.text, Catch::Contains("walker.gltf") && Catch::Contains("New project"));
  // The import is an ordinary edit of the new project: undo leaves it empty.
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().actors.empty());

  // A glTF that does not load: an error naming it, and the document as it was.
  h.tapKey(GLFW_KEY_Z, true, true);  // redo: the actor is back
  Document* before = &h.doc();
  std::string bad = f.dir.file("broken.glb");
  std::ofstream(bad) << "PK\x03\x04 not a glTF";
  h.ui->requestOpen(bad);
  h.frames(2);
  REQUIRE(h.hasWidget("prompt/dont_save"));  // the new project has unsaved changes: asked first
  h.clickWidget("prompt/dont_save");
  h.frames(2);
  CHECK(&h.doc() == before);
  CHECK(h.doc().dirty());  // the failed open kept the unsaved work
  CHECK(h.doc().project().actors.size() == 1);
  CHECK(h.ui->state().status.error);
  CHECK_THAT(h.ui->state().status.text, Catch::Contains(bad));
  REQUIRE(h.hasWidget("error/ok"));
}
