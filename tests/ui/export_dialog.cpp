// File > Export > Meshes and Volumes... and Playblast...: the dialogs' settings become the project's
// (one undoable step) and the export it starts writes the files (the harness finishes each frame's
// background job).
#include <catch2/catch.hpp>

#include <filesystem>

#include "support/editor_fixture.h"
#include "util/animorph_fixtures.h"

using namespace animorph;
using namespace animorph::test;
namespace fs = std::filesystem;

namespace {
// The walker -> flyer project (frames 30..32) as creatures.animorph in f's folder, then File > Export > item.
void openExportMenuItem(EditorFixture& f, const std::string& item) {
  auto& h = f.h;
  h.document->reset(walkerToFlyerProject("creatures", 30, 32), f.dir.file("creatures.animorph"));
  h.frames(2);
  h.clickWidget("menu/File");
  h.clickWidget("menu/Export");
  h.frames(1);
  h.clickWidget("menu/" + item);
  h.frames(2);
}
}  // namespace

TEST_CASE("File > Export > Meshes and Volumes... writes a PLY sequence, remembers its settings in the project, undo restores them",
          "[export_ui]") {
  EditorFixture f({1600.0f, 1000.0f});
  auto& h = f.h;
  openExportMenuItem(f, "Meshes and Volumes...");
  REQUIRE(h.hasWidget("export/export"));
  h.clickWidget("export/format");
  h.frames(1);
  h.clickWidget("export/format/ply");
  h.frames(2);
  auto& edit = h.ui->state().exportDialog.edit;
  CHECK(edit.format == ExportFormat::PlySequence);
  CHECK(edit.output == f.dir.file("creatures_frames"));  // the default follows the format
  edit.resolution = 16;
  h.clickWidget("export/export");
  h.frames(2);
  CHECK_FALSE(h.ui->runningJob());
  INFO(h.ui->state().status.text);
  CHECK_FALSE(h.ui->state().status.error);
  for (int frame : {30, 31, 32})
    CHECK(fs::exists(f.dir.file("creatures_frames/creatures_00" + std::to_string(frame) + ".ply")));
  const ExportSettings& saved = h.doc().project().exportSettings;
  CHECK(saved.format == ExportFormat::PlySequence);
  CHECK(saved.resolution == 16);
  CHECK(h.doc().dirty());
  REQUIRE(h.doc().undo());
  CHECK(h.doc().project().exportSettings == ExportSettings{});
}

TEST_CASE("File > Export > Playblast... checks its settings, remembers them in the project, undo restores them",
          "[export_ui]") {
  EditorFixture f({1600.0f, 1000.0f});
  auto& h = f.h;
  openExportMenuItem(f, "Playblast...");
  REQUIRE(h.hasWidget("playblast/start"));
  auto& edit = h.ui->state().playblastDialog.edit;
  CHECK(edit.output == f.dir.file("creatures.mp4"));  // beside the project
  CHECK(edit.width == 1280);
  CHECK(edit.height == 720);
  CHECK(edit.burnIn);
  // An odd width is refused in the dialog: nothing stored, nothing started.
  edit.width = 641;
  h.clickWidget("playblast/start");
  h.frames(2);
  REQUIRE(h.hasWidget("playblast/error"));
  CHECK(h.ui->state().playblastDialog.error.find("even") != std::string::npos);
  CHECK(h.doc().project().playblastSettings == PlayblastSettings{});
  edit.width = 640;
  edit.height = 360;
  edit.useTimeline = false;
  edit.first = 30;
  edit.last = 31;
  h.clickWidget("playblast/start");
  h.frames(2);
  // This harness has no GPU side (ctx.playblast is the app's): the settings are stored all the
  // same and the editor says clearly why nothing was drawn.
  const PlayblastSettings& saved = h.doc().project().playblastSettings;
  CHECK(saved.width == 640);
  CHECK(saved.height == 360);
  CHECK(saved.first == 30);
  CHECK(saved.last == 31);
  CHECK_FALSE(h.ui->runningJob());
  CHECK(h.ui->state().errorMessage.find("GPU renderer") != std::string::npos);
  CHECK_FALSE(fs::exists(f.dir.file("creatures.mp4")));
  REQUIRE(h.doc().undo());
  CHECK(h.doc().project().playblastSettings == PlayblastSettings{});
}
