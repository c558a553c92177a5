#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "core/project/project_io.h"
#include "ui/widgets/file_browser.h"
#include "support/editor_fixture.h"

using namespace animorph;
using namespace animorph::test;
namespace fs = std::filesystem;

namespace {
void touch(const std::string& path, const std::string& text = "x") { std::ofstream(path) << text; }

std::vector<std::string> names(const std::vector<DirEntry>& v) {
  std::vector<std::string> out;
  for (const auto& e : v) out.push_back(e.isDir ? e.name + "/" : e.name);
  return out;
}
}  // namespace

TEST_CASE("directory listing: directories first, sorted, filtered, hidden skipped", "[file_browser]") {
  TempDir dir;
  fs::create_directory(dir.path() / "zeta");
  fs::create_directory(dir.path() / "Alpha");
  fs::create_directory(dir.path() / ".git");
  touch(dir.file("b.animorph"));
  touch(dir.file("A.animorph"));
  touch(dir.file("walk.GLB"));
  touch(dir.file("run.gltf"));
  touch(dir.file("notes.txt"));
  touch(dir.file(".hidden.animorph"));
  auto projects = listDirectory(dir.path().string(), {".animorph"});
  REQUIRE(projects.ok());
  CHECK(names(*projects) == std::vector<std::string>{"Alpha/", "zeta/", "A.animorph", "b.animorph"});
  auto gltf = listDirectory(dir.path().string(), {".gltf", ".glb"});
  REQUIRE(gltf.ok());
  CHECK(names(*gltf) == std::vector<std::string>{"Alpha/", "zeta/", "run.gltf", "walk.GLB"});
  auto all = listDirectory(dir.path().string(), {});
  REQUIRE(all.ok());
  CHECK(all->size() == 7);
  auto missing = listDirectory(dir.file("nope"), {});
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().find("nope") != std::string::npos);
}

TEST_CASE("file browser: typed paths navigate, open, and report errors inline", "[file_browser]") {
  TempDir dir;
  fs::create_directory(dir.path() / "sub");
  touch(dir.file("sub/scene.animorph"));
  FileBrowser b;
  b.open(FileBrowser::Mode::Open, "Open", {{"Projects", {".animorph"}}}, dir.path().string());
  CHECK(b.currentDir() == dir.path().string());
  CHECK(names(b.entries()) == std::vector<std::string>{"sub/"});
  CHECK_FALSE(b.submit("sub"));  // a directory is entered
  CHECK(b.currentDir() == dir.file("sub"));
  CHECK(names(b.entries()) == std::vector<std::string>{"scene.animorph"});
  CHECK_FALSE(b.submit("missing.animorph"));
  CHECK(b.error().find("missing.animorph: no such file") != std::string::npos);
  b.navigateUp();
  CHECK(b.currentDir() == dir.path().string());
  auto chosen = b.submit(dir.file("sub/scene.animorph"));
  REQUIRE(chosen);
  CHECK(*chosen == dir.file("sub/scene.animorph"));
  CHECK_FALSE(b.isOpen());
}

TEST_CASE("file browser: saving adds the extension and confirms overwrites", "[file_browser]") {
  TempDir dir;
  touch(dir.file("old.animorph"));
  FileBrowser b;
  b.open(FileBrowser::Mode::Save, "Save", {{"Projects", {".animorph"}}}, dir.path().string(), "untitled.animorph");
  CHECK(b.pathField() == "untitled.animorph");
  auto fresh = b.submit("new");
  REQUIRE(fresh);
  CHECK(*fresh == dir.file("new.animorph"));
  b.open(FileBrowser::Mode::Save, "Save", {{"Projects", {".animorph"}}}, dir.path().string());
  CHECK_FALSE(b.submit("old"));
  CHECK(b.overwritePending() == dir.file("old.animorph"));
  CHECK_FALSE(b.confirmOverwrite(false));
  CHECK(b.isOpen());
  CHECK_FALSE(b.submit("old.animorph"));
  auto yes = b.confirmOverwrite(true);
  REQUIRE(yes);
  CHECK(*yes == dir.file("old.animorph"));
  b.open(FileBrowser::Mode::Save, "Save", {{"Projects", {".animorph"}}}, dir.path().string());
  CHECK_FALSE(b.submit(dir.file("no/such/dir/x")));
  CHECK(b.error().find("no such directory") != std::string::npos);
}

TEST_CASE("Ctrl+O opens the browser on the editor, a typed path and Enter opens the project", "[file_browser]") {
  EditorFixture f;
  auto& h = f.h;
  Project p;
  p.name = "typed";
  p.timeline.frameEnd = 33;
  REQUIRE(saveProject(p, f.dir.file("typed.animorph")).ok());
  h.tapKey(GLFW_KEY_O, true);
  REQUIRE(h.ui->state().browser.isOpen());
  CHECK(h.hasWidget("file_browser/path"));
  h.type(f.dir.file("typed.animorph"));
  h.tapKey(GLFW_KEY_ENTER);
  h.frames(1);
  CHECK_FALSE(h.ui->state().browser.isOpen());
  CHECK(h.doc().path() == f.dir.file("typed.animorph"));
  CHECK(h.doc().project().timeline.frameEnd == 33);
  CHECK(h.ui->state().prefs.recentFiles.front() == f.dir.file("typed.animorph"));
}

TEST_CASE("double-clicking entries in the browser enters directories and opens files", "[file_browser]") {
  EditorFixture f;
  auto& h = f.h;
  fs::create_directory(f.dir.path() / "projects");
  Project p;
  p.timeline.frameEnd = 12;
  REQUIRE(saveProject(p, f.dir.file("projects/clicked.animorph")).ok());
  h.doc().reset(Project{}, f.dir.file("current.animorph"));  // the browser starts in the document's directory
  h.tapKey(GLFW_KEY_O, true);
  REQUIRE(h.hasWidget("file_browser/entry/projects"));
  h.doubleClick(h.widgetCenter("file_browser/entry/projects"));
  CHECK(h.ui->state().browser.currentDir() == f.dir.file("projects"));
  h.frames(1);
  REQUIRE(h.hasWidget("file_browser/entry/clicked.animorph"));
  h.doubleClick(h.widgetCenter("file_browser/entry/clicked.animorph"));
  h.frames(1);
  CHECK(h.doc().path() == f.dir.file("projects/clicked.animorph"));
  CHECK(h.doc().project().timeline.frameEnd == 12);
}

TEST_CASE("Save As over an existing file asks first, then writes it", "[file_browser]") {
  EditorFixture f;
  auto& h = f.h;
  std::string target = f.dir.file("existing.animorph");
  REQUIRE(saveProject(Project{}, target).ok());
  h.doc().execute(std::make_unique<SetValueCommand<int>>(
      "Set range end", [](Project& p) { return &p.timeline.frameEnd; }, 96, 50));
  h.tapKey(GLFW_KEY_S, true, true);
  REQUIRE(h.ui->state().browser.isOpen());
  h.type(target);  // the pre-filled name is selected: typing replaces it
  h.tapKey(GLFW_KEY_ENTER);
  h.frames(1);
  CHECK(h.ui->state().browser.overwritePending() == target);
  REQUIRE(h.hasWidget("file_browser/overwrite_yes"));
  CHECK(loadProject(target)->timeline.frameEnd == 96);  // not written yet
  h.clickWidget("file_browser/overwrite_yes");
  h.frames(1);
  CHECK(h.doc().path() == target);
  CHECK_FALSE(h.doc().dirty());
  CHECK(loadProject(target)->timeline.frameEnd == 50);
}
