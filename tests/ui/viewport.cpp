#include <catch2/catch.hpp>

#include <cmath>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "support/editor_fixture.h"
#include "ui/viewport/viewport_input.h"

using namespace animorph;
using namespace animorph::test;

TEST_CASE("camera bindings of the Maya and Blender schemes", "[viewport]") {
  using S = CameraScheme;
  // Maya only.
  CHECK(cameraDragFor(0, true, false, false, S::Maya, false) == CameraDrag::Orbit);
  CHECK(cameraDragFor(2, true, false, false, S::Maya, false) == CameraDrag::Pan);
  CHECK(cameraDragFor(1, true, false, false, S::Maya, false) == CameraDrag::Dolly);
  CHECK(cameraDragFor(2, false, false, false, S::Maya, false) == CameraDrag::None);
  CHECK(cameraDragFor(0, false, false, false, S::Maya, false) == CameraDrag::None);  // a click: pick
  // Blender only.
  CHECK(cameraDragFor(2, false, false, false, S::Blender, false) == CameraDrag::Orbit);
  CHECK(cameraDragFor(2, false, true, false, S::Blender, false) == CameraDrag::Pan);
  CHECK(cameraDragFor(2, false, false, true, S::Blender, false) == CameraDrag::Dolly);
  CHECK(cameraDragFor(0, true, false, false, S::Blender, false) == CameraDrag::None);
  // Both at once where they do not conflict.
  CHECK(cameraDragFor(2, false, false, false, S::Maya, true) == CameraDrag::Orbit);
  CHECK(cameraDragFor(0, true, false, false, S::Blender, true) == CameraDrag::Orbit);
  CHECK(cameraDragFor(2, true, false, false, S::Blender, true) == CameraDrag::Pan);
}

TEST_CASE("viewport input: drags move the camera, clicks request picks", "[viewport]") {
  ViewportInput vi;
  OrbitCamera cam;
  ViewportRect rect{{100.0f, 50.0f}, {800.0f, 600.0f}};
  PointerInput in;
  in.pos = {500.0f, 350.0f};
  // Alt+LMB drag orbits.
  in.alt = true;
  in.down[0] = in.pressed[0] = true;
  CHECK_FALSE(vi.update(in, rect, CameraScheme::Maya, true, cam));
  CHECK(vi.activeDrag() == CameraDrag::Orbit);
  float yaw0 = cam.yawRad;
  in.pressed[0] = false;
  in.delta = {40.0f, 0.0f};
  in.pos += in.delta;
  vi.update(in, rect, CameraScheme::Maya, true, cam);
  CHECK(cam.yawRad != yaw0);
  // The drag continues outside the viewport until release; no pick from a drag.
  in.pos = {10.0f, 10.0f};
  in.delta = {0.0f, -30.0f};
  float pitch0 = cam.pitchRad;
  vi.update(in, rect, CameraScheme::Maya, true, cam);
  CHECK(cam.pitchRad != pitch0);
  in.down[0] = false;
  in.released[0] = true;
  in.delta = {0.0f, 0.0f};
  CHECK_FALSE(vi.update(in, rect, CameraScheme::Maya, true, cam));
  CHECK(vi.activeDrag() == CameraDrag::None);

  // A plain click at the viewport centre picks at NDC (0, 0).
  PointerInput c;
  c.pos = {500.0f, 350.0f};
  c.down[0] = c.pressed[0] = true;
  CHECK_FALSE(vi.update(c, rect, CameraScheme::Maya, true, cam));
  c.down[0] = c.pressed[0] = false;
  c.released[0] = true;
  auto pick = vi.update(c, rect, CameraScheme::Maya, true, cam);
  REQUIRE(pick);
  CHECK(pick->ndc.x == Approx(0.0f).margin(1e-6));
  CHECK(pick->ndc.y == Approx(0.0f).margin(1e-6));
  // Top-left corner is (-1, +1); a press that moves too far is not a click.
  c.pos = {100.0f, 50.0f};
  c.released[0] = false;
  c.down[0] = c.pressed[0] = true;
  vi.update(c, rect, CameraScheme::Maya, true, cam);
  c.down[0] = c.pressed[0] = false;
  c.released[0] = true;
  pick = vi.update(c, rect, CameraScheme::Maya, true, cam);
  REQUIRE(pick);
  CHECK(pick->ndc.x == Approx(-1.0f));
  CHECK(pick->ndc.y == Approx(1.0f));
  c.released[0] = false;
  c.down[0] = c.pressed[0] = true;
  vi.update(c, rect, CameraScheme::Maya, true, cam);
  c.pressed[0] = false;
  c.pos += glm::vec2(20.0f, 0.0f);
  vi.update(c, rect, CameraScheme::Maya, true, cam);
  c.down[0] = false;
  c.released[0] = true;
  CHECK_FALSE(vi.update(c, rect, CameraScheme::Maya, true, cam));
  // Input over another window never starts anything.
  PointerInput blocked;
  blocked.pos = {500.0f, 350.0f};
  blocked.blockedByUi = true;
  blocked.wheel = 3.0f;
  float d0 = cam.distanceM;
  vi.update(blocked, rect, CameraScheme::Maya, true, cam);
  CHECK(cam.distanceM == d0);
}

TEST_CASE("orbit camera: pan follows the mouse, dolly and wheel approach, frame fits bounds", "[viewport]") {
  OrbitCamera cam;
  glm::vec3 t0 = cam.target;
  cam.pan(100.0f, 0.0f, 600.0f);
  float expected = 100.0f * 2.0f * cam.distanceM * std::tan(0.5f * cam.fovYRad) / 600.0f;
  CHECK(glm::length(cam.target - t0) == Approx(expected).epsilon(1e-4));
  float d0 = cam.distanceM;
  cam.dolly(1.0f);
  CHECK(cam.distanceM < d0);
  cam.dolly(-3.0f);
  CHECK(cam.distanceM > d0 * 0.85f);
  cam.orbit(0.0f, 10000.0f);
  CHECK(std::abs(cam.pitchRad) < 1.5708f);  // never flips over the pole
  Bounds b;
  b.add(glm::vec3(-1.0f, 0.0f, -1.0f));
  b.add(glm::vec3(1.0f, 2.0f, 1.0f));
  cam.frame(b, 1.5f);
  CHECK(glm::length(cam.target - glm::vec3(0.0f, 1.0f, 0.0f)) < 1e-5f);
  // The bounding sphere is inside the view: distance * sin(halfFov) >= radius.
  CHECK(cam.distanceM * std::sin(0.5f * cam.fovYRad) >= 0.5f * b.diagonal());
  glm::vec4 clip = cam.projection(1.5f) * cam.view() * glm::vec4(cam.target, 1.0f);
  CHECK(clip.x / clip.w == Approx(0.0f).margin(1e-5));
  CHECK(clip.y / clip.w == Approx(0.0f).margin(1e-5));
  CHECK(clip.z / clip.w > 0.0f);
  CHECK(clip.z / clip.w < 1.0f);
}

TEST_CASE("in the editor: Alt+drag orbits, wheel zooms, click picks, F frames", "[viewport]") {
  EditorFixture f;
  f.loadHeroScene();
  auto& h = f.h;
  glm::vec2 c = h.widgetCenter("viewport");
  float yaw0 = h.ui->output().camera.yawRad;
  h.setModifiers(false, false, true);
  h.drag(c, c + glm::vec2(80.0f, 0.0f));
  h.setModifiers(false);
  h.frames(1);
  CHECK(h.ui->output().camera.yawRad != yaw0);
  float d0 = h.ui->output().camera.distanceM;
  h.wheel(c, 2.0f);
  CHECK(h.ui->output().camera.distanceM < d0);

  h.moveTo(c);
  h.press();
  ImGui::GetIO().MouseDown[0] = false;
  h.frames(1);
  REQUIRE(h.ui->output().pick);
  CHECK(h.ui->output().pick->ndc.x == Approx(0.0f).margin(0.02));
  h.frames(1);
  CHECK_FALSE(h.ui->output().pick);  // one request per click

  h.doc().selection = {"hero", -1};
  h.tapKey(GLFW_KEY_F);
  // The hero stands from y=0 to y=2 (its spine moves a little at frame 0: none).
  glm::vec3 target = h.ui->output().camera.target;
  CHECK(target.y == Approx(1.0f).margin(0.05));
  CHECK(std::abs(target.x) < 0.05f);
  CHECK(h.ui->output().camera.distanceM > 1.0f);
  CHECK(h.ui->output().camera.distanceM < 10.0f);
  // The viewport rectangle handed to the app is the layout's centre region.
  const auto& vp = h.ui->output().viewport;
  CHECK(vp.min.x == Approx(h.ui->state().layout.viewport.min.x));
  CHECK(vp.size.x > 100.0f);
}
