#include "ui/inspector/inspector_panel.h"

#include "ui/common/panel_window.h"

#include "ui/inspector/morph_panel.h"

#include <cmath>
#include <cstdio>

#include <glm/gtx/euler_angles.hpp>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/doc/actor_commands.h"
#include "ui/timeline/actor_timing.h"
#include "editor/selection_info.h"
#include "core/standin/character_pose.h"
#include "ui/inspector/standin_inspector.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

glm::vec3 quatToEulerDeg(const glm::quat& q) {
  glm::mat4 m = glm::mat4_cast(glm::normalize(q));
  float x, y, z;
  glm::extractEulerAngleZYX(m, z, y, x);  // R = Rz * Ry * Rx
  return glm::degrees(glm::vec3(x, y, z));
}

glm::quat eulerDegToQuat(const glm::vec3& deg) {
  glm::vec3 r = glm::radians(deg);
  return glm::normalize(glm::quat_cast(glm::eulerAngleZYX(r.z, r.y, r.x)));
}

namespace {

void readOnlyRow(const char* label, const std::string& value) {
  ImGui::TextDisabled("%s", label);
  ImGui::SameLine(110.0f);
  ImGui::TextWrapped("%s", value.c_str());
}

std::string vec3Text(const glm::vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.4g, %.4g, %.4g", v.x, v.y, v.z);
  return buf;
}

void drawJoint(const Character& c, int node) {
  const Node& n = c.nodes[node];
  readOnlyRow("Node", n.name.empty() ? "node " + std::to_string(node) : n.name);
  readOnlyRow("Parent", n.parent >= 0 ? c.nodes[n.parent].name : std::string("(root)"));
  readOnlyRow("Children", std::to_string(n.children.size()));
  ImGui::Separator();
  ImGui::TextUnformatted("Rest transform");
  readOnlyRow("Translation", vec3Text(n.rest.translation));
  readOnlyRow("Rotation", vec3Text(quatToEulerDeg(n.rest.rotation)) + " deg");
  readOnlyRow("Scale", vec3Text(n.rest.scale));
  if (n.mesh >= 0 && n.mesh < static_cast<int>(c.meshes.size())) {
    const Mesh& m = c.meshes[n.mesh];
    readOnlyRow("Mesh", m.name + " (" + std::to_string(m.vertexCount()) + " vertices, " +
                            std::to_string(m.triangleCount()) + " triangles)");
  }
}

// A joint (or other node) of a glTF actor: its transform and, for a rig joint, its stand-in button.
void drawCharacterNode(Document& doc, const Actor& actor, const Character* c, StandinToolState& standin,
                       StatusMessage& status) {
  ImGui::Text("Actor: %s", actor.name.c_str());
  ImGui::Separator();
  if (c && doc.selection.node < static_cast<int>(c->nodes.size())) {
    drawJoint(*c, doc.selection.node);
    if (rigNodes(*c)[size_t(doc.selection.node)])
      drawJointStandinButton(doc, *c, actor.id, doc.selection.node, standin, status);
  } else {
    ImGui::TextDisabled("The node is not in the loaded asset.");
  }
}

// Name: committed on Enter or when the field loses focus.
void drawActorName(Document& doc, const Actor& actor, InspectorState& st) {
  const std::string& id = actor.id;
  if (st.nameActorId != id || !ImGui::IsAnyItemActive()) {
    if (st.nameActorId != id || st.nameBuffer != actor.name) st.nameBuffer = actor.name;
    st.nameActorId = id;
  }
  ImGui::InputText("Name", &st.nameBuffer);
  noteWidget("inspector/name");
  if (ImGui::IsItemDeactivatedAfterEdit())
    if (auto cmd = renameActorCommand(doc.project(), id, st.nameBuffer)) doc.execute(std::move(cmd));
}

// The glTF actor's clip: a combo of the character's clips ("-" / "(no animation)" without).
void drawActorClip(Document& doc, const Actor& actor, const Character* c) {
  const std::string& id = actor.id;
  if (c && !c->clips.empty()) {
    auto clipLabel = [&](int i) {
      char buf[256];
      const AnimationClip& clip = c->clips[i];
      std::snprintf(buf, sizeof buf, "%s (%.2f s)", clip.name.empty() ? ("clip " + std::to_string(i)).c_str() : clip.name.c_str(),
                    clip.durationSec);
      return std::string(buf);
    };
    int current = actor.clip >= 0 && actor.clip < static_cast<int>(c->clips.size()) ? actor.clip : 0;
    if (ImGui::BeginCombo("Clip", clipLabel(current).c_str())) {
      for (int i = 0; i < static_cast<int>(c->clips.size()); ++i) {
        if (ImGui::Selectable(clipLabel(i).c_str(), i == current) && i != actor.clip)
          doc.execute(setActorField(doc.project(), id, &Actor::clip, i, "Set clip of " + actor.name));
      }
      ImGui::EndCombo();
    }
    noteWidget("inspector/clip");
  } else if (actor.kind == ActorKind::Gltf) {
    readOnlyRow("Clip", c ? "(no animation)" : "-");
  }
}

// Translate, rotate (Euler degrees, kept while the rotation is the one they were made from) and
// scale; each drag merges into one command.
void drawActorTransform(Document& doc, const Actor& actor, InspectorState& st, DragMerge& drag) {
  const std::string& id = actor.id;
  ImGui::Separator();
  ImGui::TextUnformatted("Transform");
  Transform tr = actor.transform;
  glm::vec3 t = tr.translation;
  bool changed = ImGui::DragFloat3("Translate", &t.x, 0.01f, 0.0f, 0.0f, "%.3f");
  noteWidget("inspector/translate");
  drag.begin(doc);
  if (changed) {
    Transform next = tr;
    next.translation = t;
    doc.execute(setActorField(doc.project(), id, &Actor::transform, next, "Move " + actor.name, id + "/translate"));
  }
  drag.end(doc);

  if (st.eulerActorId != id || st.eulerSource != tr.rotation) {
    st.eulerActorId = id;
    st.eulerSource = tr.rotation;
    st.eulerDeg = quatToEulerDeg(tr.rotation);
  }
  glm::vec3 euler = st.eulerDeg;
  changed = ImGui::DragFloat3("Rotate", &euler.x, 0.5f, 0.0f, 0.0f, "%.1f deg");
  noteWidget("inspector/rotate");
  drag.begin(doc);
  if (changed) {
    Transform next = tr;
    next.rotation = eulerDegToQuat(euler);
    st.eulerDeg = euler;
    st.eulerSource = next.rotation;
    doc.execute(setActorField(doc.project(), id, &Actor::transform, next, "Rotate " + actor.name, id + "/rotate"));
  }
  drag.end(doc);

  glm::vec3 s = tr.scale;
  changed = ImGui::DragFloat3("Scale", &s.x, 0.005f, 0.0f, 0.0f, "%.3f");
  noteWidget("inspector/scale");
  drag.begin(doc);
  if (changed) {
    Transform next = tr;
    next.scale = s;
    doc.execute(setActorField(doc.project(), id, &Actor::transform, next, "Scale " + actor.name, id + "/scale"));
  }
  drag.end(doc);
}

}  // namespace

void drawInspectorPanel(const LayoutRect& rect, Document& doc, AssetCache& assets, InspectorState& st,
                        DragMerge& drag, StatusMessage& status, StandinToolState& standin) {
  if (!beginPanelWindow("Inspector", rect)) return;
  const Actor* found = doc.project().findActor(doc.selection.actorId);
  if (!found) {
    if (doc.project().morph.enabled()) drawMorphSettings(doc, assets, st.morph, drag, status);
    else ImGui::TextDisabled("Nothing selected.");
    ImGui::End();
    return;
  }
  const Actor actor = *found;  // copy: commands below change the project
  const std::string id = actor.id;
  const Character* c = actorCharacter(doc, assets, actor);

  if (doc.selection.node >= 0 && actor.kind == ActorKind::BlobTree) {
    drawBlobNodeInspector(doc, id, doc.selection.node, st.blob, drag, status);
    ImGui::End();
    return;
  }
  if (doc.selection.node >= 0) {
    drawCharacterNode(doc, actor, c, standin, status);
    ImGui::End();
    return;
  }

  ImGui::PushItemWidth(-90.0f);
  drawActorName(doc, actor, st);
  if (actor.kind == ActorKind::BlobTree) drawBlobActorInspector(doc, id, drag, status);
  else readOnlyRow("Asset", actor.assetPath.empty() ? std::string("(none)") : actor.assetPath);
  if (!actor.assetPath.empty() && !c) {
    const AssetCache::Entry& e = assets.get(doc.resolveAsset(actor.assetPath));
    ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.35f, 1.0f), "%s", e.error.c_str());
  }
  drawActorClip(doc, actor, c);
  // Timing.
  drawActorTiming(doc, actor, drag, "inspector");
  ImGui::SameLine();
  bool visible = actor.visible;
  if (ImGui::Checkbox("Visible", &visible))
    doc.execute(setActorField(doc.project(), id, &Actor::visible, visible,
                              std::string(visible ? "Show " : "Hide ") + actor.name));
  drawActorTransform(doc, actor, st, drag);
  ImGui::PopItemWidth();

  drawParticlesSection(doc, id, st.particles);
  if (c) {
    ImGui::Separator();
    ImGui::TextDisabled("%zu meshes, %zu vertices, %zu triangles, %zu joints, %zu clips", c->meshes.size(),
                        c->totalVertices(), c->totalTriangles(), c->totalJoints(), c->clips.size());
    for (const std::string& w : c->report.warnings) ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s", w.c_str());
    drawStandinInspector(doc, *c, id, standin, drag, status);
  }
  ImGui::End();
}

}  // namespace animorph
