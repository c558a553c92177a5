#include <catch2/catch.hpp>

#include <cmath>

#include "core/camera/camera.h"

using namespace animorph;

namespace {
OrbitCamera frontCamera() {
  OrbitCamera c;
  c.target = {0, 0, 0};
  c.yawRad = 0;
  c.pitchRad = 0;
  c.distanceM = 5;
  return c;
}
float dist(glm::vec3 a, glm::vec3 b) { return glm::length(a - b); }
}  // namespace

TEST_CASE("orbit camera frame and matrices", "[view][camera]") {
  OrbitCamera c = frontCamera();
  CHECK(dist(c.eye(), {0, 0, 5}) < 1e-5f);
  CHECK(dist(c.forward(), {0, 0, -1}) < 1e-6f);
  CHECK(dist(c.right(), {1, 0, 0}) < 1e-6f);
  CHECK(dist(c.up(), {0, 1, 0}) < 1e-6f);
  glm::mat4 v = c.view();
  CHECK(dist(glm::vec3(v * glm::vec4(0, 0, 0, 1)), {0, 0, -5}) < 1e-5f);
  // Orthonormal frame at any yaw/pitch.
  c.yawRad = 2.1f;
  c.pitchRad = -0.7f;
  CHECK(std::abs(glm::dot(c.forward(), c.right())) < 1e-6f);
  CHECK(std::abs(glm::dot(c.forward(), c.up())) < 1e-6f);
  CHECK(glm::length(c.up()) == Approx(1.0f));
  CHECK(dist(c.eye() + c.forward() * c.distanceM, c.target) < 1e-5f);
}

TEST_CASE("projection is Vulkan clip space: y down, depth 0..1", "[view][camera]") {
  OrbitCamera c = frontCamera();
  glm::mat4 vp = c.viewProjection(1.5f);
  auto ndc = [&](glm::vec3 p) {
    glm::vec4 h = vp * glm::vec4(p, 1);
    return glm::vec3(h) / h.w;
  };
  CHECK(ndc({0, 1, 0}).y < 0.0f);  // world up is screen up: negative NDC y
  CHECK(ndc({1, 0, 0}).x > 0.0f);
  CHECK(ndc(c.eye() + c.forward() * c.nearM()).z == Approx(0.0f).margin(1e-5));
  CHECK(ndc(c.eye() + c.forward() * c.farM()).z == Approx(1.0f).margin(1e-4));
  // The top edge of the view cone lands on NDC y = -1.
  float t = std::tan(0.5f * c.fovYRad) * c.distanceM;
  CHECK(ndc({0, t, 0}).y == Approx(-1.0f).margin(1e-5));
  CHECK(ndc({t * 1.5f, 0, 0}).x == Approx(1.0f).margin(1e-5));
}

TEST_CASE("pixels and rays are inverse of each other", "[view][camera]") {
  OrbitCamera c;
  c.target = {0.3f, 1.0f, -2.0f};
  c.yawRad = 0.8f;
  c.pitchRad = 0.4f;
  c.distanceM = 7.0f;
  glm::vec2 vp(800, 450);
  glm::vec3 centre = c.worldToPixel(c.target, vp);
  CHECK(centre.x == Approx(400.0f).margin(1e-3));
  CHECK(centre.y == Approx(225.0f).margin(1e-3));
  for (glm::vec3 p : {glm::vec3(1, 2, -1), glm::vec3(-1, 0.5f, -3), glm::vec3(0.3f, 1.5f, -2.5f)}) {
    glm::vec3 px = c.worldToPixel(p, vp);
    Ray ray = c.rayThroughPixel(px.x, px.y, vp);
    CHECK(glm::length(ray.direction) == Approx(1.0f));
    CHECK(dist(ray.origin, c.eye()) < 1e-5f);
    // p lies on the ray.
    float along = glm::dot(p - ray.origin, ray.direction);
    CHECK(dist(ray.origin + along * ray.direction, p) < 1e-3f);
  }
}

TEST_CASE("orbit, pan and dolly", "[view][camera]") {
  OrbitCamera c = frontCamera();
  c.orbit(100, 0);  // drag right: the eye swings to the left (-x)
  CHECK(c.eye().x < 0.0f);
  CHECK(c.distanceM == 5.0f);
  CHECK(dist(c.target, {0, 0, 0}) < 1e-6f);
  c.orbit(0, 1e6f);  // pitch is clamped short of the pole
  CHECK(c.pitchRad == Approx(OrbitCamera::kMaxPitchRad));
  CHECK(std::isfinite(c.view()[0][0]));

  // Pan: the target point follows the cursor by exactly the dragged pixels.
  OrbitCamera p = frontCamera();
  glm::vec2 vp(640, 480);
  glm::vec3 anchor(0, 0, 0);
  glm::vec3 before = p.worldToPixel(anchor, vp);
  p.pan(40, -25, vp.y);
  glm::vec3 after = p.worldToPixel(anchor, vp);
  CHECK(after.x - before.x == Approx(40.0f).margin(1e-2));
  CHECK(after.y - before.y == Approx(-25.0f).margin(1e-2));

  OrbitCamera d = frontCamera();
  d.dolly(1);
  CHECK(d.distanceM == Approx(5.0f * 0.85f));
  d.dolly(-2);
  CHECK(d.distanceM == Approx(5.0f / 0.85f));
  d.dolly(1e4f);
  CHECK(d.distanceM >= OrbitCamera::kMinDistanceM);
}

TEST_CASE("frame puts the bounds fully in view", "[view][camera]") {
  Bounds b;
  b.add({2, 0, -1});
  b.add({4, 3, 1});
  for (float aspect : {0.5f, 1.0f, 2.0f}) {
    OrbitCamera c;
    c.yawRad = 0.5f;
    c.pitchRad = 0.3f;
    c.frame(b, aspect);
    CHECK(dist(c.target, b.center()) < 1e-6f);
    glm::vec2 vp(1000.0f * aspect, 1000.0f);
    for (int i = 0; i < 8; ++i) {
      glm::vec3 corner(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
      glm::vec3 px = c.worldToPixel(corner, vp);
      CHECK(px.x >= 0.0f);
      CHECK(px.x <= vp.x);
      CHECK(px.y >= 0.0f);
      CHECK(px.y <= vp.y);
      CHECK(px.z > 0.0f);
      CHECK(px.z < 1.0f);
    }
  }
  OrbitCamera unchanged = frontCamera();
  unchanged.frame(Bounds{}, 1.0f);
  CHECK(unchanged.distanceM == 5.0f);
}

TEST_CASE("pickTriangle returns the nearest hit", "[view][camera]") {
  // Two parallel unit squares facing +z at z = 0 and z = -1, and a triangle off to the side.
  std::vector<glm::vec3> pos = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                {-1, -1, 0},  {1, -1, 0},  {1, 1, 0},  {-1, 1, 0},
                                {5, 5, 0},    {6, 5, 0},   {5, 6, 0}};
  std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 8, 9, 10};
  Ray ray{{0.25f, 0.5f, 5}, {0, 0, -1}};
  auto hit = pickTriangle(ray, pos, idx);
  REQUIRE(hit);
  CHECK((hit->triangle == 2 || hit->triangle == 3));  // the near square
  CHECK(hit->distance == Approx(5.0f));
  CHECK(dist(hit->position, {0.25f, 0.5f, 0}) < 1e-5f);
  // Barycentrics reproduce the hit point.
  glm::vec3 rebuilt = hit->barycentric.x * pos[idx[3 * hit->triangle]] +
                      hit->barycentric.y * pos[idx[3 * hit->triangle + 1]] +
                      hit->barycentric.z * pos[idx[3 * hit->triangle + 2]];
  CHECK(dist(rebuilt, hit->position) < 1e-5f);
  // From behind, the far square is nearest.
  auto back = pickTriangle({{0.25f, 0.5f, -5}, {0, 0, 1}}, pos, idx);
  REQUIRE(back);
  CHECK(back->triangle <= 1);
  CHECK(back->distance == Approx(4.0f));
  // Misses, rays pointing away, and out-of-range indices.
  CHECK_FALSE(pickTriangle({{3, 3, 5}, {0, 0, -1}}, pos, idx));
  CHECK_FALSE(pickTriangle({{0, 0, 5}, {0, 0, 1}}, pos, idx));
  std::vector<uint32_t> broken = {0, 1, 99};
  CHECK_FALSE(pickTriangle(ray, pos, broken));
  // Picking through a camera pixel.
  OrbitCamera cam;
  cam.target = {5.3f, 5.3f, 0};
  cam.yawRad = 0;
  cam.pitchRad = 0;
  cam.distanceM = 4;
  glm::vec2 vp(300, 200);
  Ray centre = cam.rayThroughPixel(150, 100, vp);
  auto tri = pickTriangle(centre, pos, idx);
  REQUIRE(tri);
  CHECK(tri->triangle == 4);
}
