#include <catch2/catch.hpp>

#include <fstream>

#include "ui/common/layout.h"
#include "support/editor_fixture.h"
#include "ui/common/prefs.h"

using namespace animorph;
using namespace animorph::test;

TEST_CASE("dragging a splitter resizes the panel and the size persists in the preferences", "[layout]") {
  EditorFixture f;
  float before = f.h.ui->state().layout.outliner.size.x;
  glm::vec2 c = f.h.widgetCenter("splitter/outliner");
  f.h.drag(c, c + glm::vec2(60.0f, 0.0f));
  f.h.frames(1);
  float after = f.h.ui->state().layout.outliner.size.x;
  CHECK(after == Approx(before + 60.0f));
  CHECK(f.h.ui->state().layout.viewport.min.x == Approx(after + kSplitterThicknessPx));

  // Timeline splitter: dragging up makes the timeline taller.
  float tlBefore = f.h.ui->state().layout.timeline.size.y;
  glm::vec2 t = f.h.widgetCenter("splitter/timeline");
  f.h.drag(t, t + glm::vec2(0.0f, -40.0f));
  f.h.frames(1);
  CHECK(f.h.ui->state().layout.timeline.size.y == Approx(tlBefore + 40.0f));

  // Written on release; a new editor starts with the same layout.
  auto saved = loadPreferences(f.dir.file("config/prefs.json"));
  REQUIRE(saved.ok());
  CHECK(saved->outlinerWidth == Approx(after));
  CHECK(saved->timelineHeight == Approx(tlBefore + 40.0f));
  EditorUI again(f.dir.file("config/prefs.json"));
  CHECK(again.state().prefs.outlinerWidth == Approx(after));
}

TEST_CASE("splitter drags are clamped so the viewport never vanishes", "[layout]") {
  EditorFixture f;
  glm::vec2 c = f.h.widgetCenter("splitter/outliner");
  f.h.drag(c, {1270.0f, c.y}, 0, 4);
  f.h.frames(1);
  const LayoutRects& r = f.h.ui->state().layout;
  CHECK(r.viewport.size.x >= kMinViewportPx - 0.5f);
  CHECK(r.inspector.size.x >= kMinPanelPx - 0.5f);
  CHECK(r.inspector.max().x == Approx(1280.0f));
  auto saved = loadPreferences(f.dir.file("config/prefs.json"));
  REQUIRE(saved.ok());
  CHECK(saved->outlinerWidth <= 1280.0f - kMinViewportPx - kMinPanelPx - 2 * kSplitterThicknessPx + 0.5f);
}

TEST_CASE("layout rectangles tile the window without overlap", "[layout]") {
  for (glm::vec2 display : {glm::vec2(1280, 800), glm::vec2(1920, 1080), glm::vec2(640, 480), glm::vec2(300, 200)}) {
    for (float w : {0.0f, 200.0f, 5000.0f}) {
      LayoutSizes s{w, w, w};
      LayoutRects r = computeLayout(display, 20.0f, 22.0f, s);
      // Rows: menu | upper area | timeline splitter | timeline | status.
      CHECK(r.outliner.min.y == 20.0f);
      CHECK(r.timelineSplitter.max().y == Approx(r.timeline.min.y));
      CHECK(r.timeline.max().y == Approx(r.statusBar.min.y));
      CHECK(r.statusBar.max().y == Approx(display.y));
      // Columns: outliner | splitter | viewport | splitter | inspector.
      CHECK(r.outlinerSplitter.min.x == Approx(r.outliner.max().x));
      CHECK(r.viewport.min.x == Approx(r.outlinerSplitter.max().x));
      CHECK(r.inspectorSplitter.min.x == Approx(r.viewport.max().x));
      CHECK(r.inspector.min.x == Approx(r.inspectorSplitter.max().x));
      CHECK(r.inspector.max().x == Approx(display.x));
      CHECK(r.viewport.size.x >= 0.0f);
      CHECK(r.viewport.size.y >= 0.0f);
      if (display.x >= 1000.0f) {
        CHECK(r.viewport.size.x >= kMinViewportPx - 1e-3f);
        CHECK(r.outliner.size.x >= kMinPanelPx - 1e-3f);
      }
    }
  }
}

TEST_CASE("a broken preferences file is ignored with a message", "[layout]") {
  TempDir dir;
  std::string path = dir.file("prefs.json");
  { std::ofstream(path) << "{\"layout\": 12"; }
  EditorUI ui(path);
  CHECK(ui.state().prefs == Preferences{});
  CHECK(ui.state().status.error);
  CHECK(ui.state().status.text.find("prefs.json") != std::string::npos);
}

TEST_CASE("docked editors take the bottom of the viewport's column, side by side, and tile it", "[layout]") {
  for (glm::vec2 display : {glm::vec2(1280, 800), glm::vec2(1920, 1080), glm::vec2(640, 480)}) {
    for (DockedEditors d : {DockedEditors{true, false}, DockedEditors{false, true}, DockedEditors{true, true}}) {
      const LayoutRects plain = computeLayout(display, 20.0f, 22.0f, LayoutSizes{});
      const LayoutRects r = computeLayout(display, 20.0f, 22.0f, LayoutSizes{}, d);
      // Rows of the column: viewport | editors splitter | editors, ending where the viewport ended.
      CHECK(r.viewport.min.y == Approx(plain.viewport.min.y));
      CHECK(r.editorsSplitter.min.y == Approx(r.viewport.max().y));
      const LayoutRect& first = d.correspondence ? r.correspondence : r.curves;
      const LayoutRect& last = d.curves ? r.curves : r.correspondence;
      CHECK(first.min.y == Approx(r.editorsSplitter.max().y));
      CHECK(first.max().y == Approx(plain.viewport.max().y));
      // Columns: the viewport's own, split at the divider when both are open.
      CHECK(first.min.x == Approx(plain.viewport.min.x));
      CHECK(last.max().x == Approx(plain.viewport.max().x));
      if (d.correspondence && d.curves) {
        CHECK(r.editorsDivider.min.x == Approx(r.correspondence.max().x));
        CHECK(r.curves.min.x == Approx(r.editorsDivider.max().x));
        CHECK(r.correspondence.size.x == Approx(r.curves.size.x).margin(1.0f));
      } else {
        CHECK(r.editorsDivider.size.x == 0.0f);
        CHECK((d.correspondence ? r.curves : r.correspondence).size.x == 0.0f);
      }
      if (display.y >= 800.0f) CHECK(r.viewport.size.y >= kMinViewportPx - 1e-3f);
    }
  }
  // A huge area keeps the viewport its minimum.
  LayoutSizes big;
  big.editorsHeight = 5000.0f;
  const LayoutRects r = computeLayout({1280, 800}, 20.0f, 22.0f, big, {true, true});
  CHECK(r.viewport.size.y == Approx(kMinViewportPx));
}

TEST_CASE("the correspondence and curve editors dock below the viewport, the splitters size them, the sizes persist",
          "[layout]") {
  EditorFixture f({1600.0f, 1000.0f});
  const LayoutRect before = f.h.ui->state().layout.viewport;
  f.h.ui->state().correspondence.visible = true;
  f.h.ui->state().curveEditor.visible = true;
  f.h.frames(2);
  const LayoutRects& r = f.h.ui->state().layout;
  // The viewport keeps its top and width and ends above the editors; the windows sit on their rectangles.
  CHECK(r.viewport.min.y == Approx(before.min.y));
  CHECK(r.viewport.size.x == Approx(before.size.x));
  CHECK(r.viewport.size.y < before.size.y - 200.0f);
  REQUIRE(f.h.hasWidget("corr/window"));
  REQUIRE(f.h.hasWidget("curve/window"));
  const WidgetRect corr = *f.h.ui->widgets().find("corr/window"), curves = *f.h.ui->widgets().find("curve/window");
  CHECK(corr.min.y >= r.viewport.max().y);
  CHECK(curves.min.y >= r.viewport.max().y);
  CHECK(corr.max.x <= curves.min.x + 0.5f);
  CHECK(corr.min.x == Approx(r.viewport.min.x));
  CHECK(curves.max.x == Approx(r.viewport.max().x));

  // The splitter above them: dragging it up makes the area taller; the divider moves the split.
  const float h0 = r.correspondence.size.y, w0 = r.correspondence.size.x;
  glm::vec2 s = f.h.widgetCenter("splitter/editors");
  f.h.drag(s, s + glm::vec2(0.0f, -50.0f));
  f.h.frames(1);
  CHECK(r.correspondence.size.y == Approx(h0 + 50.0f));
  glm::vec2 d = f.h.widgetCenter("splitter/editors_divider");
  f.h.drag(d, d + glm::vec2(80.0f, 0.0f));
  f.h.frames(1);
  CHECK(r.correspondence.size.x == Approx(w0 + 80.0f).margin(1.0f));
  auto saved = loadPreferences(f.dir.file("config/prefs.json"));
  REQUIRE(saved.ok());
  CHECK(saved->editorsHeight == Approx(h0 + 50.0f));

  // Closing both gives the viewport its whole column back.
  f.h.ui->state().correspondence.visible = false;
  f.h.ui->state().curveEditor.visible = false;
  f.h.frames(2);
  CHECK(r.viewport.size.y == Approx(before.size.y));
  CHECK_FALSE(f.h.hasWidget("splitter/editors"));
}
