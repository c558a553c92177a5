#include <catch2/catch.hpp>

#include "editor/click_selection.h"

using namespace animorph;

namespace {
ScenePick hitAt(const char* actor, float distance) {
  ScenePick p;
  p.actorId = actor;
  p.distance = distance;
  return p;
}
}  // namespace

TEST_CASE("a click selects the marker's node, else the nearest surface's actor, else nothing", "[pick]") {
  const Selection current{"hero", 3};
  const BlobGuidePick guide{"blob", 7, 2.0f};

  // A skeleton marker wins over a surface in front of it.
  CHECK(selectionAfterClick(current, guide, hitAt("gear", 0.5f), false) == Selection{"blob", 7});
  // A surface selects its actor (not a node).
  CHECK(selectionAfterClick(current, std::nullopt, hitAt("gear", 0.5f), false) == Selection{"gear", -1});
  // Nothing under the cursor: cleared, unless Shift extends the selection.
  CHECK(selectionAfterClick(current, std::nullopt, std::nullopt, false) == Selection{});
  CHECK(selectionAfterClick(current, std::nullopt, std::nullopt, true) == current);

  // Of several surfaces along the ray, the nearest.
  auto n = nearerPick(hitAt("far", 3.0f), hitAt("near", 1.0f));
  REQUIRE(n);
  CHECK(n->actorId == "near");
  CHECK(nearerPick(std::nullopt, hitAt("only", 9.0f))->actorId == "only");
  CHECK(nearerPick(hitAt("only", 9.0f), std::nullopt)->actorId == "only");
  CHECK_FALSE(nearerPick(std::nullopt, std::nullopt));
}
