// File > Export...: the dialog's settings become the project's (one undoable step) and the export
// it starts writes the files (the harness finishes each frame's background job).
#include <catch2/catch.hpp>

#include <filesystem>

#include "support/editor_fixture.h"
#include "util/animorph_fixtures.h"

using namespace animorph;
using namespace animorph::test;
namespace fs = std::filesystem;

TEST_CASE("File > Export... writes a PLY sequence, remembers its settings in the project, undo restores them",
          "[export_ui]") {
  EditorFixture f({1600.0f, 1000.0f});
  auto& h = f.h;
  h.document->reset(walkerToFlyerProject("creatures", 30, 32), f.dir.file("creatures.animorph"));
  h.frames(2);
  h.clickWidget("menu/File");
  h.clickWidget("menu/Export...");
  h.frames(2);
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
