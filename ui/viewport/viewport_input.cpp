#include "ui/viewport/viewport_input.h"

#include <imgui.h>

namespace animorph {
namespace {
// Alt+RMB / Ctrl+MMB dolly: 100 pixels of drag is three wheel notches.
constexpr float kDollyStepsPerPixel = 0.03f;
constexpr float kClickSlopPx = 4.0f;
}

CameraDrag cameraDragFor(int button, bool alt, bool shift, bool ctrl, CameraScheme scheme, bool otherSchemeToo) {
  bool maya = scheme == CameraScheme::Maya || otherSchemeToo;
  bool blender = scheme == CameraScheme::Blender || otherSchemeToo;
  if (alt && maya) {
    if (button == 0) return CameraDrag::Orbit;
    if (button == 2) return CameraDrag::Pan;
    if (button == 1) return CameraDrag::Dolly;
  }
  if (!alt && blender && button == 2) {
    if (shift) return CameraDrag::Pan;
    if (ctrl) return CameraDrag::Dolly;
    return CameraDrag::Orbit;
  }
  return CameraDrag::None;
}

std::optional<PickRequest> ViewportInput::update(const PointerInput& in, const ViewportRect& rect,
                                                 CameraScheme scheme, bool otherSchemeToo, OrbitCamera& camera) {
  std::optional<PickRequest> pick;
  bool inside = rect.contains(in.pos) && !in.blockedByUi;

  // Continue or end the current drag.
  if (drag_ != CameraDrag::None) {
    if (!in.down[dragButton_]) {
      drag_ = CameraDrag::None;
      dragButton_ = -1;
    } else if (in.delta != glm::vec2(0.0f)) {
      switch (drag_) {
        case CameraDrag::Orbit: camera.orbit(in.delta.x, in.delta.y); break;
        case CameraDrag::Pan: camera.pan(in.delta.x, in.delta.y, rect.size.y); break;
        case CameraDrag::Dolly: camera.dolly((in.delta.x - in.delta.y) * kDollyStepsPerPixel); break;
        case CameraDrag::None: break;
      }
    }
  }

  // Start a drag or a click.
  if (drag_ == CameraDrag::None && inside) {
    for (int b = 0; b < 3; ++b) {
      if (!in.pressed[b]) continue;
      CameraDrag d = cameraDragFor(b, in.alt, in.shift, in.ctrl, scheme, otherSchemeToo);
      if (d != CameraDrag::None) {
        drag_ = d;
        dragButton_ = b;
        clickCandidate_ = false;
        break;
      }
      if (b == 0 && !in.alt) {
        clickCandidate_ = true;
        pressPos_ = in.pos;
      }
    }
  }

  if (clickCandidate_) {
    if (glm::length(in.pos - pressPos_) > kClickSlopPx || drag_ != CameraDrag::None) {
      clickCandidate_ = false;
    } else if (in.released[0]) {
      clickCandidate_ = false;
      if (rect.contains(in.pos) && rect.size.x > 0.0f && rect.size.y > 0.0f) {
        PickRequest r;
        r.windowPos = in.pos;
        r.ndc = {(in.pos.x - rect.min.x) / rect.size.x * 2.0f - 1.0f,
                 1.0f - (in.pos.y - rect.min.y) / rect.size.y * 2.0f};
        r.extend = in.shift;
        pick = r;
      }
    }
  }

  if (inside && in.wheel != 0.0f && drag_ == CameraDrag::None) camera.dolly(in.wheel);
  return pick;
}

PointerInput pointerFromImGui(const ImGuiIO& io, bool blockedByUi) {
  PointerInput p;
  p.pos = {io.MousePos.x, io.MousePos.y};
  bool valid = io.MousePos.x > -1e30f && io.MouseDelta.x > -1e30f;
  p.delta = valid ? glm::vec2(io.MouseDelta.x, io.MouseDelta.y) : glm::vec2(0.0f);
  for (int b = 0; b < 3; ++b) {
    p.down[b] = io.MouseDown[b];
    p.pressed[b] = io.MouseClicked[b];
    p.released[b] = io.MouseReleased[b];
  }
  p.wheel = io.MouseWheel;
  p.alt = io.KeyAlt;
  p.shift = io.KeyShift;
  p.ctrl = io.KeyCtrl;
  p.blockedByUi = blockedByUi;
  return p;
}

}  // namespace animorph
