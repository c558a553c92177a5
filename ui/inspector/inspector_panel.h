#pragma once
// Inspector (right panel): the selected actor's name, asset, clip, timing,
// visibility and transform (rotation edited as Euler degrees, stored as a
// quaternion), or a selected joint's name, parent and rest transform
// (read-only). Every edit is a command; one drag is one undo step.
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "ui/inspector/blob_inspector.h"
#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "ui/widgets/drag_merge.h"
#include "ui/common/layout.h"
#include "ui/inspector/morph_panel.h"
#include "ui/inspector/particles_panel.h"
#include "ui/viewport/standin_tool.h"

namespace animorph {

struct InspectorState {
  // Euler angles shown for the actor's rotation. Kept between frames so a
  // drag through gimbal-lock angles does not jump; refreshed whenever the
  // stored quaternion changes under us (undo, another panel).
  std::string eulerActorId;
  glm::quat eulerSource{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 eulerDeg{0.0f};
  std::string nameBuffer;
  std::string nameActorId;
  BlobInspectorState blob;  // a selected BlobTree node
  MorphPanelState morph;    // the morph's settings (nothing selected)
  ParticlesPanelState particles;  // a BlobTree actor's Particles section
};

// Refused edits (BlobTree nodes) report to status.
// standin: the selected stand-in segment (a morph actor's inspector lists its segments).
void drawInspectorPanel(const LayoutRect& rect, Document& doc, AssetCache& assets, InspectorState& st,
                        DragMerge& drag, StatusMessage& status, StandinToolState& standin);

// XYZ Euler angles in degrees (R = Rz * Ry * Rx) of q, and back.
glm::vec3 quatToEulerDeg(const glm::quat& q);
glm::quat eulerDegToQuat(const glm::vec3& deg);

}  // namespace animorph
