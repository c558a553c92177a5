// Offscreen rendering on lavapipe: pixels where the camera and the CPU skinning
// say they must be, grid, wireframe, overlays, resizing; no validation errors.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu_fixture.h"
#include "gpu/present/offscreen_target.h"
#include "core/rig/skinning.h"
#include "gpu/render/scene_renderer.h"

using namespace animorph;
using namespace animorph::gpu;
using animorph::test::differs;
using animorph::test::pixelAt;

namespace {

const glm::vec4 kBackground{0.1f, 0.2f, 0.3f, 1.0f};
const glm::vec4 kRed{0.85f, 0.2f, 0.15f, 1.0f};

struct Rig {
  std::unique_ptr<Context> ctx;
  test::SceneTarget draw;
  std::unique_ptr<GpuMesh> mesh;
  Mesh cpuMesh;
};

Rig makeRig(uint32_t w, uint32_t h, SceneRendererSettings settings = {}) {
  Rig r;
  r.ctx = test::makeTestContext();
  r.draw = test::makeSceneTarget(*r.ctx, w, h, settings);
  r.cpuMesh = test::twoQuadMesh();
  auto mesh = GpuMesh::upload(*r.ctx, r.cpuMesh, settings.forceEdgeListWireframe);
  INFO(mesh.error());
  REQUIRE(mesh.ok());
  r.mesh = std::move(*mesh);
  return r;
}

const RgbaImage& render(Rig& r, const OrbitCamera& cam, const Scene& scene) { return test::renderScene(r.draw, cam, scene); }

OrbitCamera frontCamera() {
  OrbitCamera c;
  c.target = glm::vec3(0.0f);
  c.yawRad = 0.0f;
  c.pitchRad = 0.0f;
  c.distanceM = 6.0f;
  return c;
}

Scene meshScene(const Rig& r, const std::vector<glm::mat4>& joints) {
  Scene s;
  s.options.background = kBackground;
  s.options.grid = false;
  s.options.axisIndicator = false;
  MeshDraw d;
  d.mesh = r.mesh.get();
  d.jointMatrices = joints;
  d.color = kRed;
  s.meshes.push_back(d);
  return s;
}

// The 3x3 neighbourhood of the pixel of world, for features one pixel wide.
std::vector<glm::u8vec4> around(const RgbaImage& img, const OrbitCamera& cam, const glm::vec3& world) {
  glm::vec3 p = cam.worldToPixel(world, {float(img.width), float(img.height)});
  REQUIRE(p.x >= 1.0f);
  REQUIRE(p.y >= 1.0f);
  REQUIRE(p.x < float(img.width) - 1.0f);
  REQUIRE(p.y < float(img.height) - 1.0f);
  std::vector<glm::u8vec4> out;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) out.push_back(img.at(uint32_t(int(p.x) + dx), uint32_t(int(p.y) + dy)));
  return out;
}

float luminance(glm::u8vec4 p) { return 0.2126f * p.r + 0.7152f * p.g + 0.0722f * p.b; }

std::vector<glm::mat4> liftJoints() {
  // Joint 1 lifts by 1.25: quad B (0.8 on joint 1, 0.2 on identities) moves up by exactly 1.
  std::vector<glm::mat4> j(6, glm::mat4(1.0f));
  j[1] = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1.25f, 0));
  return j;
}

}  // namespace

TEST_CASE("mesh pixels land where the camera projects them", "[gpu][render]") {
  Rig r = makeRig(256, 192);
  OrbitCamera cam = frontCamera();
  std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  const RgbaImage& img = render(r, cam, meshScene(r, joints));
  // Inside both quads: shaded red; between them and around: background.
  glm::u8vec4 a = pixelAt(img, cam, {-1, 0, 0});
  CHECK(differs(a, kBackground, 10));
  CHECK(int(a.r) > int(a.g) + 60);
  CHECK(differs(pixelAt(img, cam, {1, 0, 0}), kBackground, 10));
  CHECK_FALSE(differs(pixelAt(img, cam, {0, 0, 0}), kBackground));
  CHECK_FALSE(differs(pixelAt(img, cam, {-1, 0.8f, 0}), kBackground));
  CHECK_FALSE(differs(pixelAt(img, cam, {2, 0, 0}), kBackground));
  CHECK_FALSE(differs(img.at(0, 0), kBackground, 1));  // the cleared rectangle, exactly
  CHECK(img.at(0, 0).a == 255);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU skinning moves vertices where CPU skinning does (8 influences)", "[gpu][render][skinning]") {
  Rig r = makeRig(256, 192);
  OrbitCamera cam = frontCamera();
  std::vector<glm::mat4> joints = liftJoints();
  std::vector<glm::vec3> skinned, normals;
  skinMesh(r.cpuMesh, joints, skinned, normals);
  // Quad B's vertices are 4..7; the CPU says it moved up by one.
  glm::vec3 center(0.0f);
  for (int v = 4; v < 8; ++v) center += 0.25f * skinned[v];
  REQUIRE(glm::length(center - glm::vec3(1, 1, 0)) < 1e-5f);

  const RgbaImage& img = render(r, cam, meshScene(r, joints));
  CHECK(differs(pixelAt(img, cam, center), kBackground, 10));
  CHECK_FALSE(differs(pixelAt(img, cam, {1, 0, 0}), kBackground));  // where it was
  for (int v = 4; v < 8; ++v) {
    glm::vec3 inside = center + 0.85f * (skinned[v] - center);
    glm::vec3 outside = center + 1.15f * (skinned[v] - center);
    INFO("vertex " << v);
    CHECK(differs(pixelAt(img, cam, inside), kBackground, 10));
    CHECK_FALSE(differs(pixelAt(img, cam, outside), kBackground));
  }
  // Quad A, bound to the identity joint, did not move.
  CHECK(differs(pixelAt(img, cam, {-1, 0, 0}), kBackground, 10));
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("skinned normals follow the joint rotation", "[gpu][render][skinning]") {
  Rig r = makeRig(256, 192);
  OrbitCamera cam = frontCamera();
  // Quad B turned 70 degrees about the vertical through its centre: it must shade
  // darker than quad A, which faces the viewer (with untransformed normals both
  // would face the headlight alike).
  glm::mat4 turn = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0)) *
                   glm::rotate(glm::mat4(1.0f), glm::radians(70.0f), glm::vec3(0, 1, 0)) *
                   glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0));
  std::vector<glm::mat4> joints(6, turn);
  joints[0] = glm::mat4(1.0f);
  const RgbaImage& img = render(r, cam, meshScene(r, joints));
  float a = luminance(pixelAt(img, cam, {-1, 0, 0}));
  float b = luminance(pixelAt(img, cam, {1, 0, 0}));
  CHECK(differs(pixelAt(img, cam, {1, 0, 0}), kBackground, 5));
  CHECK(b < 0.75f * a);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("single-sided meshes cull back faces, double-sided ones do not", "[gpu][render]") {
  Rig r = makeRig(256, 192);
  OrbitCamera behind = frontCamera();
  behind.yawRad = 3.14159265f;  // looking from -Z at the quads' backs
  std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  Scene scene = meshScene(r, joints);
  CHECK(test::countDiffering(render(r, behind, scene), kBackground) == 0);
  CHECK(differs(pixelAt(render(r, frontCamera(), scene), frontCamera(), {-1, 0, 0}), kBackground, 10));
  scene.meshes[0].doubleSided = true;
  const RgbaImage& img = render(r, behind, scene);
  glm::u8vec4 back = pixelAt(img, behind, {-1, 0, 0});
  CHECK(differs(back, kBackground, 10));
  CHECK(int(back.r) > int(back.g) + 60);  // lit like a front face (two-sided shading)
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("the ground grid appears, with coloured axes, and fades with distance", "[gpu][render][grid]") {
  Rig r = makeRig(320, 240);
  OrbitCamera cam;
  cam.target = glm::vec3(0.0f);
  cam.yawRad = 0.3f;
  cam.pitchRad = 0.35f;
  cam.distanceM = 6.0f;
  Scene scene;
  const glm::vec4 black(0, 0, 0, 1);
  scene.options.background = black;
  scene.options.axisIndicator = false;
  const RgbaImage& img = render(r, cam, scene);
  auto maxOf = [](const std::vector<glm::u8vec4>& px, int channel) {
    int m = 0;
    for (auto p : px) m = std::max(m, int(p[channel]));
    return m;
  };
  // A minor line (x = 1) shows; the middle of a cell is background.
  CHECK(maxOf(around(img, cam, {1, 0, 1.5f}), 1) > 20);
  CHECK_FALSE(differs(pixelAt(img, cam, {0.5f, 0, 1.5f}), black));
  // The X axis (z = 0) is red, the Z axis (x = 0) blue.
  auto xAxis = around(img, cam, {2, 0, 0});
  CHECK(maxOf(xAxis, 0) > maxOf(xAxis, 2) + 40);
  auto zAxis = around(img, cam, {0, 0, 2});
  CHECK(maxOf(zAxis, 2) > maxOf(zAxis, 0) + 40);
  // 40 m away the grid has faded out.
  for (auto p : around(img, cam, {1, 0, -40})) CHECK_FALSE(differs(p, black, 4));
  // Turning the grid off leaves only background.
  scene.options.grid = false;
  CHECK(test::countDiffering(render(r, cam, scene), black) == 0);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("wireframe overlay draws the edges over the surface", "[gpu][render][wireframe]") {
  for (bool edgeList : {false, true}) {
    DYNAMIC_SECTION((edgeList ? "edge-list path" : "polygon-mode path")) {
      SceneRendererSettings settings;
      settings.forceEdgeListWireframe = edgeList;
      Rig r = makeRig(256, 192, settings);
      CHECK(r.draw.renderer->wireframeUsesEdgeLists() == (edgeList || !r.ctx->supportsWireframeFill()));
      OrbitCamera cam = frontCamera();
      std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
      Scene scene = meshScene(r, joints);
      RgbaImage solid = render(r, cam, scene);
      scene.options.wireframe = true;
      scene.options.wireColor = glm::vec4(0, 0, 0, 1);
      RgbaImage wire = render(r, cam, scene);
      size_t changed = 0, changedOutside = 0;
      for (uint32_t y = 0; y < wire.height; ++y)
        for (uint32_t x = 0; x < wire.width; ++x) {
          if (wire.at(x, y) == solid.at(x, y)) continue;
          ++changed;
          // Edges lie on the surface: any change is on or next to a shaded pixel.
          bool nearSurface = false;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              nearSurface |= differs(solid.at(uint32_t(int(x) + dx), uint32_t(int(y) + dy)), kBackground);
          changedOutside += !nearSurface;
        }
      CHECK(changed > 100);  // 4 outlines and 2 diagonals of ~38 px quads
      CHECK(changedOutside == 0);
      // The diagonal through quad A's centre is drawn dark.
      int darkest = 255;
      for (auto p : around(wire, cam, {-1, 0, 0})) darkest = std::min(darkest, int(p.r));
      CHECK(darkest < 40);
      CHECK(r.ctx->validationErrorCount() == 0);
    }
  }
}

TEST_CASE("overlay lines draw on top, depth-tested lines are hidden", "[gpu][render][lines]") {
  Rig r = makeRig(256, 192);
  OrbitCamera cam = frontCamera();
  std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  const uint32_t green = packRgba({0.1f, 0.9f, 0.1f, 1.0f});
  auto isGreen = [](glm::u8vec4 p) { return p.g > 180 && p.r < 80; };
  auto anyGreen = [&](const RgbaImage& img, glm::vec3 world) {
    bool found = false;
    for (auto p : around(img, cam, world)) found |= isGreen(p);
    return found;
  };
  // A line behind quad A (z = -1), and one in the open (visible either way).
  Scene scene = meshScene(r, joints);
  scene.lines.line({-1.4f, 0.1f, -1}, {-0.6f, 0.1f, -1}, green);
  scene.lines.line({-0.4f, -1.5f, 0}, {0.4f, -1.5f, 0}, green);
  RgbaImage depthTested = render(r, cam, scene);
  CHECK_FALSE(anyGreen(depthTested, {-1, 0.1f, -1}));
  CHECK(anyGreen(depthTested, {0, -1.5f, 0}));

  scene.overlay = scene.lines;
  scene.lines.clear();
  RgbaImage onTop = render(r, cam, scene);
  CHECK(anyGreen(onTop, {-1, 0.1f, -1}));
  CHECK(anyGreen(onTop, {0, -1.5f, 0}));
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("axis indicator in the lower-left corner", "[gpu][render]") {
  Rig r = makeRig(200, 150);
  OrbitCamera cam = frontCamera();
  Scene scene;
  scene.options.background = kBackground;
  scene.options.grid = false;
  scene.options.axisIndicator = true;
  const RgbaImage& with = render(r, cam, scene);
  size_t inCorner = 0, elsewhere = 0;
  for (uint32_t y = 0; y < with.height; ++y)
    for (uint32_t x = 0; x < with.width; ++x) {
      bool corner = x < 6 + 72 && y >= with.height - 6 - 72;
      (corner ? inCorner : elsewhere) += differs(with.at(x, y), kBackground);
    }
  CHECK(inCorner > 40);
  CHECK(elsewhere == 0);
  scene.options.axisIndicator = false;
  CHECK(test::countDiffering(render(r, cam, scene), kBackground) == 0);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("drawing into a viewport rectangle leaves the rest of the target alone", "[gpu][render]") {
  Rig r = makeRig(200, 100);
  OrbitCamera cam = frontCamera();
  std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  Scene scene = meshScene(r, joints);
  const glm::vec4 clear(1, 1, 1, 1);
  Status recorded;
  Status s = r.draw.target->render(
      [&](VkCommandBuffer cmd) { recorded = r.draw.renderer->record(cmd, r.draw.target->serial(), {100, 20, 100, 80}, cam, scene); }, clear);
  REQUIRE(s.ok());
  REQUIRE(recorded.ok());
  const RgbaImage& img = r.draw.target->image();
  CHECK_FALSE(differs(img.at(50, 50), clear));    // left of the rectangle
  CHECK_FALSE(differs(img.at(150, 10), clear));   // above it
  CHECK_FALSE(differs(img.at(102, 22), kBackground));  // its cleared corner
  // Quad A's centre, projected into the rectangle.
  glm::vec3 p = cam.worldToPixel({-1, 0, 0}, {100.0f, 80.0f});
  CHECK(differs(img.at(100 + uint32_t(p.x), 20 + uint32_t(p.y)), kBackground, 10));
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("two viewports in one frame keep their own cameras, poses and lines", "[gpu][render]") {
  Rig r = makeRig(400, 150);
  OrbitCamera left = frontCamera();
  OrbitCamera right = frontCamera();
  right.target = {1, 1, 0};  // looks at the lifted quad B
  right.distanceM = 3.0f;
  std::vector<glm::mat4> rest(6, glm::mat4(1.0f));
  // The second viewport needs more joint matrices and line vertices than the
  // initial ring capacity, so its buffers grow while the first viewport's
  // commands still read the old ones.
  std::vector<glm::mat4> lifted = liftJoints();
  lifted.resize(700, glm::mat4(1.0f));
  Scene a = meshScene(r, rest);
  Scene b = meshScene(r, lifted);
  b.options.background = glm::vec4(0.3f, 0.3f, 0.3f, 1.0f);
  for (int i = 0; i < 6000; ++i) b.overlay.line({1.3f, 1.3f, 0}, {1.31f, 1.3f, 0}, packRgba({0, 1, 0, 1}));
  const ViewportRect ra{0, 0, 200, 150}, rb{200, 0, 200, 150};
  for (int frame = 0; frame < 3; ++frame) {  // also reuses both ring slots after growth
    Status sa, sb;
    Status s = r.draw.target->render([&](VkCommandBuffer cmd) {
      sa = r.draw.renderer->record(cmd, r.draw.target->serial(), ra, left, a);
      sb = r.draw.renderer->record(cmd, r.draw.target->serial(), rb, right, b);
    });
    REQUIRE(s.ok());
    REQUIRE(sa.ok());
    REQUIRE(sb.ok());
    const RgbaImage& img = r.draw.target->image();
    glm::vec2 vp(200, 150);
    auto at = [&](const ViewportRect& rect, const OrbitCamera& cam, glm::vec3 w) {
      glm::vec3 p = cam.worldToPixel(w, vp);
      return img.at(uint32_t(rect.x) + uint32_t(p.x), uint32_t(p.y));
    };
    // Left: rest pose seen from the front camera.
    CHECK(differs(at(ra, left, {1, 0, 0}), kBackground, 10));
    CHECK_FALSE(differs(at(ra, left, {1, 1, 0}), kBackground));
    // Right: quad B lifted, seen from its own camera, and its overlay line.
    CHECK(differs(at(rb, right, {1, 1, 0}), b.options.background, 10));
    CHECK_FALSE(differs(at(rb, right, {1, 0.2f, 0}), b.options.background));
    glm::u8vec4 line = at(rb, right, {1.305f, 1.3f, 0});
    CHECK(line.g > 200);
  }
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("resizing an offscreen target", "[gpu][render]") {
  Rig r = makeRig(64, 48);
  OrbitCamera cam = frontCamera();
  std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  Scene scene = meshScene(r, joints);
  CHECK(render(r, cam, scene).pixels.size() == 64u * 48u * 4u);
  REQUIRE(r.draw.target->resize(300, 120).ok());
  CHECK(r.draw.target->extent().width == 300);
  CHECK(r.draw.target->extent().height == 120);
  const RgbaImage& img = render(r, cam, scene);
  CHECK(img.width == 300);
  CHECK(img.height == 120);
  CHECK(img.pixels.size() == 300u * 120u * 4u);
  CHECK(differs(pixelAt(img, cam, {-1, 0, 0}), kBackground, 10));
  CHECK(differs(pixelAt(img, cam, {1, 0, 0}), kBackground, 10));
  CHECK_FALSE(differs(pixelAt(img, cam, {0, 0, 0}), kBackground));
  CHECK_FALSE(differs(img.at(5, 5), kBackground));
  // A bad size is refused and the target keeps working at its old size.
  Status bad = r.draw.target->resize(0, 10);
  CHECK_FALSE(bad.ok());
  CHECK(bad.error().find("0x10") != std::string::npos);
  CHECK(r.draw.target->extent().width == 300);
  CHECK(render(r, cam, scene).width == 300);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("ring buffers grow for many draws and lines", "[gpu][render]") {
  Rig r = makeRig(128, 96);
  OrbitCamera cam = frontCamera();
  std::vector<glm::mat4> joints(600, glm::mat4(1.0f));  // more than the initial 256 matrices
  Scene scene = meshScene(r, joints);
  for (int i = 0; i < 3; ++i) scene.meshes.push_back(scene.meshes[0]);
  for (int i = 0; i < 5000; ++i) scene.overlay.line({-3, -2, 0}, {-3, -2, 0.01f}, packRgba({1, 1, 1, 1}));
  for (int frame = 0; frame < 3; ++frame) {
    const RgbaImage& img = render(r, cam, scene);
    CHECK(differs(pixelAt(img, cam, {-1, 0, 0}), kBackground, 10));
  }
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("PNG output", "[gpu][render]") {
  Rig r = makeRig(64, 48);
  std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  const RgbaImage& img = render(r, frontCamera(), meshScene(r, joints));
  std::string path = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/animorph_gpu_test.png";
  REQUIRE(writePng(path, img).ok());
  FILE* f = std::fopen(path.c_str(), "rb");
  REQUIRE(f);
  unsigned char sig[8] = {};
  CHECK(std::fread(sig, 1, 8, f) == 8);
  std::fclose(f);
  std::remove(path.c_str());
  CHECK(sig[1] == 'P');
  CHECK(sig[2] == 'N');
  CHECK(sig[3] == 'G');
  Status bad = writePng("/nonexistent-dir/x.png", img);
  CHECK_FALSE(bad.ok());
  CHECK(bad.error().find("/nonexistent-dir/x.png") != std::string::npos);
}

TEST_CASE("weight overlay: heat colours per vertex on the skinned mesh", "[gpu][render][paint]") {
  Rig r = makeRig(256, 192);
  OrbitCamera cam = frontCamera();
  const std::vector<glm::mat4> joints = liftJoints();
  // Quad A (vertices 0..3) unpainted, quad B (4..7) fully painted.
  const std::vector<float> weights = {0, 0, 0, 0, 1, 1, 1, 1};
  Scene s = meshScene(r, joints);
  s.meshes.clear();
  WeightOverlayDraw w;
  w.mesh = r.mesh.get();
  w.jointMatrices = joints;
  w.weights = weights;
  s.weightOverlays.push_back(w);
  const RgbaImage& img = render(r, cam, s);
  glm::u8vec4 a = pixelAt(img, cam, {-1, 0, 0});
  glm::u8vec4 b = pixelAt(img, cam, {1, 1, 0});  // skinned: quad B is lifted by 1
  CHECK(int(a.b) > int(a.r) + 80);  // 0: blue
  CHECK(int(b.r) > int(b.b) + 80);  // 1: red
  CHECK_FALSE(differs(pixelAt(img, cam, {1, 0, 0}), kBackground, 10));  // B's unskinned place is empty
  // A weight array of the wrong length draws nothing rather than reading past it.
  s.weightOverlays[0].weights = std::span<const float>(weights.data(), 5);
  const RgbaImage& none = render(r, cam, s);
  CHECK_FALSE(differs(pixelAt(none, cam, {-1, 0, 0}), kBackground));
  CHECK(r.ctx->validationErrorCount() == 0);
}
