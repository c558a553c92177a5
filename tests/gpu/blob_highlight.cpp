// The correspondence editor's hover highlight (gpu/frame/scene_from_frame.h addBlobHighlight): a
// primitive solid, a big sub-tree a translucent tint under a solid outline.
#include <catch2/catch.hpp>

#include "gpu/frame/scene_from_frame.h"

using namespace animorph;

namespace {

BlobGuides markersOnALine(int n) {
  BlobGuides g;
  for (int i = 0; i < n; ++i) g.markers.push_back({glm::vec3(0.01f * float(i), 0.0f, 0.0f), 7});
  g.lines.push_back({glm::vec3(0.0f), glm::vec3(0.01f * float(n), 0.0f, 0.0f), 7});
  return g;
}

int alphaOf(uint32_t rgba) { return int(rgba >> 24); }

}  // namespace

TEST_CASE("a hovered primitive is highlighted solid, a sub-tree of thousands as a tint under its outline box",
          "[highlight]") {
  gpu::Scene few, many;
  gpu::addBlobHighlight(markersOnALine(3), few);
  gpu::addBlobHighlight(markersOnALine(2000), many);
  // Few guides: every vertex solid, no box (3 octahedra of 12 edges and one line).
  REQUIRE(few.overlay.vertices().size() == size_t(2 * (3 * 12 + 1)));
  for (const auto& v : few.overlay.vertices()) CHECK(alphaOf(v.rgba) == 255);
  // Many: the 12 edges of the outline box solid, a sample of the guides faint (every 13th of the
  // 2001: 154 of the markers and the line).
  const auto& vs = many.overlay.vertices();
  CHECK(gpu::highlightGuideStride(2001) == 13);
  REQUIRE(vs.size() == size_t(2 * (12 + 154 * 12 + 1)));
  int solid = 0, faint = 0;
  for (const auto& v : vs) (alphaOf(v.rgba) == 255 ? solid : faint) += 1;
  CHECK(solid == 24);
  CHECK(faint == int(vs.size()) - 24);
  CHECK(alphaOf(vs.back().rgba) < 48);  // 24 / 154 of 255
  CHECK(gpu::highlightGuideAlpha(24) == 1.0f);
  CHECK(gpu::highlightGuideAlpha(48) == Approx(0.5f));
  CHECK(gpu::highlightGuideAlpha(100000) == Approx(gpu::kMinHighlightAlpha));
}
