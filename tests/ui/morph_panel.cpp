#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "support/editor_fixture.h"
#include "ui/timeline/timeline_panel.h"

using namespace animorph;
using namespace animorph::test;

namespace {
void addMorph(EditorFixture& f) { f.loadHeroMorphScene(); }
}  // namespace

TEST_CASE("morph settings show with nothing selected, and a marker drag is one undo step", "[morph]") {
  EditorFixture f;
  addMorph(f);
  auto& h = f.h;
  REQUIRE(h.hasWidget("morph/markers"));
  // DragInt4: the first of the four fields is marker A. Drag it to the right.
  auto r = *h.ui->widgets().find("morph/markers");
  const float w = (r.max.x - r.min.x) / 4.0f;
  glm::vec2 a{r.min.x + 0.5f * w, r.center().y};
  h.drag(a, a + glm::vec2(40.0f, 0.0f));
  const MorphMarkers after = h.doc().project().morph.markers;
  CHECK(after.a > 10);
  CHECK(after.a <= after.b);  // kept in order
  CHECK(h.doc().history().size() == 1);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().morph.markers == MorphMarkers{10, 20, 30, 40});
  CHECK_FALSE(h.doc().dirty());
}

TEST_CASE("dragging a morph marker on the timeline moves it in one undo step without scrubbing", "[morph]") {
  EditorFixture f;
  addMorph(f);
  auto& h = f.h;
  auto r = *h.ui->widgets().find("timeline/ruler");
  const TimelineState& tls = h.ui->state().timeline;
  auto xOf = [&](double frame) {
    return static_cast<float>(r.min.x + (frame - tls.viewStartFrame) * (r.max.x - r.min.x) /
                                            (tls.viewEndFrame - tls.viewStartFrame));
  };
  const int frameBefore = h.doc().project().timeline.currentFrame;
  // Marker B's handle sits just right of its line, above the stage bands.
  glm::vec2 handle{xOf(20) + 6.0f, r.max.y - 15.0f};
  h.drag(handle, {xOf(26) + 6.0f, handle.y});
  const MorphMarkers m = h.doc().project().morph.markers;
  CHECK(m.b == 26);
  CHECK(m.a == 10);
  CHECK(m.c == 30);
  CHECK(h.doc().project().timeline.currentFrame == frameBefore);  // no scrub
  CHECK(h.doc().history().size() == 1);
  // Dragging past C stops at C: markers stay ordered.
  h.drag({xOf(26) + 6.0f, handle.y}, {xOf(35) + 6.0f, handle.y});
  CHECK(h.doc().project().morph.markers.b == 30);
  h.tapKey(GLFW_KEY_Z, true);
  h.tapKey(GLFW_KEY_Z, true);
  CHECK(h.doc().project().morph.markers == MorphMarkers{10, 20, 30, 40});
}
