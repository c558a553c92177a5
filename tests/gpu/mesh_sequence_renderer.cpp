// The offscreen sequence renderer behind playblasts and PNG frames: the camera it is given is the
// one it draws with (the editor's playblast passes the viewport's), else it frames the bounds.
#include <catch2/catch.hpp>

#include "gpu_fixture.h"
#include "gpu/frame/mesh_sequence_renderer.h"

using namespace animorph;
using namespace animorph::gpu;

namespace {

// An axis-aligned cube of side 1 centred at the origin, 8 vertices, 12 outward triangles.
TriangleMesh unitCube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f});
  m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
               2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  for (const glm::vec3& p : m.positions) m.normals.push_back(glm::normalize(p));
  return m;
}

// Mean x of the pixels that differ from the top-left corner (the background), and their count.
std::pair<double, size_t> meshPixels(const RgbaImage& im) {
  const glm::u8vec4 bg = im.at(0, 0);
  double sumX = 0.0;
  size_t n = 0;
  for (uint32_t y = 0; y < im.height; ++y)
    for (uint32_t x = 0; x < im.width; ++x)
      if (im.at(x, y) != bg) {
        sumX += x;
        ++n;
      }
  return {n ? sumX / double(n) : 0.0, n};
}

}  // namespace

TEST_CASE("sequence renderer: a given camera is the one it draws with, else it frames the bounds",
          "[gpu][render][playblast]") {
  test::prepareGpuEnvironment();
  ViewOptions view;
  view.showGrid = false;
  view.showAxes = false;
  auto r = MeshSequenceRenderer::create(160, 90, view);
  REQUIRE(r);
  const TriangleMesh cube = unitCube();
  Bounds b;
  for (const auto& p : cube.positions) b.add(p);

  (*r)->frameBounds(b);
  auto framed = (*r)->render(cube);
  REQUIRE(framed);
  const auto [framedX, framedCount] = meshPixels(**framed);
  CHECK(framedCount > 160 * 90 / 20);              // the cube fills a good part of the picture
  CHECK(std::abs(framedX - 80.0) < 8.0);           // in the middle

  // The same orbit aimed 2 m to the cube's right (along the camera's right vector): the cube
  // moves left in the picture and shrinks (the camera is farther).
  OrbitCamera cam;
  cam.distanceM = 6.0f;
  cam.target = cam.right() * 2.0f;
  (*r)->setCamera(cam);
  auto aside = (*r)->render(cube);
  REQUIRE(aside);
  const auto [asideX, asideCount] = meshPixels(**aside);
  CHECK(asideCount > 0);
  CHECK(asideCount < framedCount);
  CHECK(asideX < 60.0);
  CHECK((*r)->validationErrors() == 0);
}
