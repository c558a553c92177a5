// The particle view's spheres on lavapipe (ParticleSpheresDraw, particle_sphere shaders): round,
// where the camera projects them, shaded, depth from their true surface (a sphere drawn first in
// front of one drawn later wins; a small sphere whose centre is inside a large one shows only its cap).
#include <catch2/catch.hpp>

#include "gpu_fixture.h"
#include "gpu/render/particle_spheres.h"
#include "gpu/render/scene_renderer.h"

using namespace animorph;
using namespace animorph::gpu;
using namespace animorph::test;

namespace {

const glm::vec4 kBackground{0.1f, 0.2f, 0.3f, 1.0f};

OrbitCamera camera() {
  OrbitCamera c;
  c.target = glm::vec3(0.0f);
  c.yawRad = 0.3f;
  c.pitchRad = 0.2f;
  c.distanceM = 6.0f;
  return c;
}

Scene emptyScene() {
  Scene s;
  s.options.background = kBackground;
  s.options.grid = false;
  s.options.axisIndicator = false;
  return s;
}

float luminance(glm::u8vec4 p) { return 0.2126f * p.r + 0.7152f * p.g + 0.0722f * p.b; }
bool reddish(glm::u8vec4 p) { return p.r > p.g + 40 && p.r > p.b + 40; }
bool greenish(glm::u8vec4 p) { return p.g > p.r + 40 && p.g > p.b + 40; }
bool bluish(glm::u8vec4 p) { return p.b > p.r + 40 && p.b > p.g + 40; }

ParticleSpheresDraw spheres(std::vector<glm::vec4> s, glm::vec4 color) {
  ParticleSpheresDraw d;
  d.spheres = std::move(s);
  d.color = color;
  return d;
}

}  // namespace

TEST_CASE("particle spheres are round discs where the camera projects their centres", "[gpu][render][particles]") {
  auto ctx = makeTestContext();
  SceneTarget r = makeSceneTarget(*ctx, 320, 240);
  const OrbitCamera cam = camera();
  const glm::vec3 right = cam.right(), up = cam.up();
  const float radius = 0.35f;
  const glm::vec3 a(-1.2f, 0.3f, 0.0f), b(1.1f, -0.4f, 0.5f);
  Scene scene = emptyScene();
  scene.particles.push_back(spheres({glm::vec4(a, radius), glm::vec4(b, radius)}, {0.85f, 0.2f, 0.15f, 1.0f}));
  const RgbaImage& img = renderScene(r, cam, scene);
  for (const glm::vec3& c : {a, b}) {
    CHECK(reddish(pixelAt(img, cam, c)));
    CHECK(reddish(pixelAt(img, cam, c + 0.8f * radius * right)));
    CHECK(reddish(pixelAt(img, cam, c - 0.8f * radius * up)));
    // Outside the disc, though inside the triangle drawn around it (its top corner is 2 r up).
    CHECK_FALSE(differs(pixelAt(img, cam, c + 1.5f * radius * up), kBackground));
    CHECK_FALSE(differs(pixelAt(img, cam, c - 1.25f * radius * right), kBackground));
    // Shaded as a sphere: the middle (facing the eye) brighter than near the rim.
    CHECK(luminance(pixelAt(img, cam, c)) > luminance(pixelAt(img, cam, c + 0.93f * radius * right)) + 10.0f);
  }
  CHECK_FALSE(differs(pixelAt(img, cam, 0.5f * (a + b)), kBackground));
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("particle spheres take the depth of their surface", "[gpu][render][particles]") {
  auto ctx = makeTestContext();
  SceneTarget r = makeSceneTarget(*ctx, 320, 240);
  const OrbitCamera cam = camera();
  const glm::vec3 toEye = glm::normalize(cam.eye() - cam.target), right = cam.right();
  const glm::vec3 c(0.0f);
  SECTION("a near sphere drawn first hides the far one drawn after it") {
    Scene scene = emptyScene();
    scene.particles.push_back(spheres({glm::vec4(c + 1.0f * toEye, 0.3f)}, {0.85f, 0.2f, 0.15f, 1.0f}));
    scene.particles.push_back(spheres({glm::vec4(c - 1.0f * toEye, 0.6f)}, {0.2f, 0.85f, 0.15f, 1.0f}));
    const RgbaImage& img = renderScene(r, cam, scene);
    CHECK(reddish(pixelAt(img, cam, c + 1.0f * toEye)));
    // Beside the near sphere, the far (larger on screen) one shows.
    CHECK(greenish(pixelAt(img, cam, c - 1.0f * toEye + 0.45f * right)));
  }
  SECTION("a small sphere whose centre is inside a large one shows only its cap") {
    // Large: r 0.5 at c; small: r 0.3, its centre 0.25 nearer the eye (inside the large one, 0.25
    // behind its front). In the middle the small one's front (0.55) beats the large one's (0.5);
    // 0.27 to the side the large one's (0.42) beats it (0.38). A triangle at the small sphere's
    // centre depth would be hidden everywhere.
    Scene scene = emptyScene();
    scene.particles.push_back(spheres({glm::vec4(c, 0.5f)}, {0.2f, 0.85f, 0.15f, 1.0f}));
    scene.particles.push_back(spheres({glm::vec4(c + 0.25f * toEye, 0.3f)}, {0.85f, 0.2f, 0.15f, 1.0f}));
    const RgbaImage& img = renderScene(r, cam, scene);
    CHECK(reddish(pixelAt(img, cam, c + 0.25f * toEye)));
    CHECK(greenish(pixelAt(img, cam, c + 0.25f * toEye + 0.27f * right)));
    CHECK(greenish(pixelAt(img, cam, c + 0.25f * toEye - 0.27f * right)));
  }
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("particle spheres from a particle draw follow its model matrix", "[gpu][render][particles]") {
  ParticleDraw d;
  d.model = glm::mat4(2.0f);
  d.model[3] = glm::vec4(1.0f, 2.0f, 3.0f, 1.0f);
  d.centres = {glm::vec3(0.5f, 0.0f, 0.0f), glm::vec3(0.0f)};
  d.radii = {0.1f, 0.0f};
  const ParticleSpheresDraw s = particleSpheres(d, {1, 0, 0, 1}, true);
  REQUIRE(s.spheres.size() == 2);
  CHECK(s.spheres[0].x == Approx(2.0f));
  CHECK(s.spheres[0].y == Approx(2.0f));
  CHECK(s.spheres[0].w == Approx(0.2f));
  CHECK(s.spheres[1].w == Approx(2e-3f));  // at least 1 mm before the scale
  CHECK(s.selected);
  CHECK(s.colors.empty());  // no colours of its own: the draw's colour
  d.colors = {glm::vec3(1.0f, 0.5f, 0.0f), glm::vec3(0.0f, 0.0f, 2.0f)};
  const ParticleSpheresDraw c = particleSpheres(d, {1, 0, 0, 1}, false);
  REQUIRE(c.colors.size() == 2);
  CHECK(c.colors[0] == (0xFF000000u | (128u << 8) | 255u));  // r in the low byte, alpha 255
  CHECK(c.colors[1] == 0xFFFF0000u);                         // clamped to 1
}

TEST_CASE("particle spheres of one draw each take their own colour", "[gpu][render][particles]") {
  auto ctx = makeTestContext();
  SceneTarget r = makeSceneTarget(*ctx, 320, 240);
  const OrbitCamera cam = camera();
  const glm::vec3 a(-1.2f, 0.3f, 0.0f), b(1.1f, -0.4f, 0.5f), c(0.0f, -1.0f, 0.0f);
  Scene scene = emptyScene();
  ParticleDraw d;
  d.centres = {a, b, c};
  d.radii = {0.35f, 0.35f, 0.35f};
  d.colors = {glm::vec3(0.9f, 0.1f, 0.1f), glm::vec3(0.1f, 0.2f, 0.9f), glm::vec3(0.1f, 0.9f, 0.1f)};
  scene.particles.push_back(particleSpheres(d, {0.85f, 0.85f, 0.85f, 1.0f}, false));
  // A draw without colours of its own keeps its one colour.
  scene.particles.push_back(spheres({glm::vec4(0.0f, 1.2f, 0.0f, 0.3f)}, {0.85f, 0.2f, 0.15f, 1.0f}));
  const RgbaImage& img = renderScene(r, cam, scene);
  CHECK(reddish(pixelAt(img, cam, a)));
  CHECK(bluish(pixelAt(img, cam, b)));
  CHECK(greenish(pixelAt(img, cam, c)));
  CHECK(reddish(pixelAt(img, cam, glm::vec3(0.0f, 1.2f, 0.0f))));
  CHECK(ctx->validationErrorCount() == 0);
}
