#include "ui/inspector/blob_inspector.h"
#include "ui/common/blob_time.h"

#include <cmath>
#include <cstdio>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/blobtree/tree_edit.h"
#include "core/doc/blobtree_commands.h"
#include "core/math/euler.h"
#include "core/project/animation_end_cache.h"
#include "core/scene/scene_frame.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

void run(Document& doc, Result<std::unique_ptr<Command>> cmd, StatusMessage& status) {
  if (cmd) doc.execute(std::move(*cmd));
  else status = {cmd.error(), true};
}

bool keyedAt(const BlobTree& tree, const ParamAddress& a, double timeSec) {
  int n = keyCount(tree, a);
  if (n < 2) return false;
  for (int k = 0; k < n; ++k) {
    double t = 0.0;
    ParamSample v;
    if (keyAt(tree, {a, k}, t, v) && std::abs(t - timeSec) < 1e-6) return true;
  }
  return false;
}

// One parameter row: key button, label, field. Returns nothing; edits go through commands.
void paramRow(Document& doc, const std::string& actorId, const BlobTree& tree, const ParamAddress& a,
              const std::string& label, double timeSec, DragMerge& drag, StatusMessage& status,
              const std::string& widgetKey, bool color = false) {
  ParamSample value;
  if (!sampleParam(tree, a, timeSec, value)) return;
  ImGui::PushID(widgetKey.c_str());
  bool animated = isAnimated(tree, a);
  if (keyButton("##key", keyedAt(tree, a, timeSec), animated))
    run(doc, setBlobParamCommand(doc.project(), actorId, a, timeSec, value, true), status);
  noteWidget(widgetKey + "/key");
  if (ImGui::IsItemHovered()) {
    if (animated) ImGui::SetTooltip("Set a key at this frame (%d keys)", keyCount(tree, a));
    else ImGui::SetTooltip("Key at this frame (a second key at another frame animates it)");
  }
  ImGui::SameLine();
  std::string mergeKey = "blobparam/" + actorId + "/" + std::to_string(a.node) + "/" + std::to_string(a.param) + "/" +
                         std::to_string(a.point);
  bool changed = false;
  ParamSample next = value;
  if (animated) ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0.32f, 0.28f, 0.12f, 1.0f));
  if (auto* f = std::get_if<float>(&value)) {
    float v = *f;
    changed = ImGui::DragFloat(label.c_str(), &v, 0.005f, 0.0f, 0.0f, "%.4g");
    next = v;
  } else if (auto* p = std::get_if<glm::vec3>(&value); p && color) {
    // A colour parameter (sRGB, 0..1): a swatch that opens a picker, and the components to type in.
    glm::vec3 v = *p;
    changed = ImGui::ColorEdit3(label.c_str(), &v.x, ImGuiColorEditFlags_Float);
    next = glm::clamp(v, 0.0f, 1.0f);
  } else if (auto* p = std::get_if<glm::vec3>(&value)) {
    glm::vec3 v = *p;
    changed = ImGui::DragFloat3(label.c_str(), &v.x, 0.005f, 0.0f, 0.0f, "%.3f");
    next = v;
  } else {
    glm::vec3 e = eulerDegreesOf(std::get<glm::quat>(value));
    changed = ImGui::DragFloat3(label.c_str(), &e.x, 0.5f, 0.0f, 0.0f, "%.1f deg");
    next = quatFromEulerDegrees(e);
  }
  if (animated) ImGui::PopStyleColor();
  noteWidget(widgetKey);
  drag.begin(doc);
  if (changed) run(doc, setBlobParamCommand(doc.project(), actorId, a, timeSec, next, false, mergeKey), status);
  drag.end(doc);
  ImGui::PopID();
}

}  // namespace

bool keyButton(const char* id, bool keyedHere, bool animated) {
  float h = ImGui::GetFrameHeight();
  ImVec2 p = ImGui::GetCursorScreenPos();
  bool clicked = ImGui::InvisibleButton(id, ImVec2(h, h));
  bool hovered = ImGui::IsItemHovered();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  ImVec2 c(p.x + h * 0.5f, p.y + h * 0.5f);
  float r = h * 0.3f;
  ImVec2 q[4] = {{c.x, c.y - r}, {c.x + r, c.y}, {c.x, c.y + r}, {c.x - r, c.y}};
  ImU32 yellow = IM_COL32(240, 200, 60, 255), grey = IM_COL32(130, 130, 140, 255);
  ImU32 col = animated ? yellow : grey;
  if (hovered) col = IM_COL32(255, 235, 140, 255);
  if (keyedHere) dl->AddQuadFilled(q[0], q[1], q[2], q[3], col);
  else dl->AddQuad(q[0], q[1], q[2], q[3], col, 1.5f);
  return clicked;
}


void drawBlobNodeInspector(Document& doc, const std::string& actorId, int nodeId, BlobInspectorState& st,
                           DragMerge& drag, StatusMessage& status) {
  const Actor* actor = doc.project().findActor(actorId);
  if (!actor || actor->kind != ActorKind::BlobTree) return;
  const BlobTree tree = actor->blobTree;  // copy: commands below replace the actor's tree
  const BlobNode* node = tree.find(nodeId);
  if (!node) {
    ImGui::TextDisabled("Node %d is not in the tree.", nodeId);
    return;
  }
  const double t = blobTreeTimeNow(doc, *actor);
  const NodeTypeInfo& info = nodeTypeInfo(node->type);
  ImGui::Text("Actor: %s", actor->name.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s node %d: %s", info.category, node->id, info.doc);
  ImGui::PopStyleColor();
  ImGui::Separator();

  ImGui::PushItemWidth(-110.0f);
  if (st.nameNode != nodeId || st.nameActor != actorId || !ImGui::IsAnyItemActive()) {
    st.nameBuffer = node->name;
    st.nameNode = nodeId;
    st.nameActor = actorId;
  }
  ImGui::Dummy(ImVec2(ImGui::GetFrameHeight(), 0.0f));
  ImGui::SameLine();
  ImGui::InputText("Name", &st.nameBuffer);
  noteWidget("inspector/blob/name");
  if (ImGui::IsItemDeactivatedAfterEdit() && st.nameBuffer != node->name)
    run(doc, renameBlobNodeCommand(doc.project(), actorId, nodeId, st.nameBuffer), status);
  ImGui::TextDisabled("Type %s  |  tree time %.3f s", info.name, t);

  if (!info.params.empty()) {
    ImGui::Separator();
    ImGui::TextUnformatted("Parameters");
  }
  for (size_t i = 0; i < info.params.size(); ++i) {
    const ParamSpec& spec = info.params[i];
    if (spec.kind != ParamKind::Vec3List) {
      paramRow(doc, actorId, tree, {nodeId, int(i), -1}, spec.name, t, drag, status,
               std::string("inspector/blob/") + spec.name, isColorParam(spec));
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", spec.doc);
      continue;
    }
    // Control points: one row per point, plus add/remove.
    const ControlPoints& pts = std::get<ControlPoints>(node->params[i]);
    ImGui::TextDisabled("%s (%zu points)", spec.name, pts.size());
    ImGui::PushID(int(i));
    for (size_t k = 0; k < pts.size(); ++k) {
      std::string label = std::string(spec.name) + "[" + std::to_string(k) + "]";
      paramRow(doc, actorId, tree, {nodeId, int(i), int(k)}, label, t, drag, status, "inspector/blob/" + label);
    }
    if (ImGui::SmallButton("+ point")) {
      run(doc,
          editBlobTree(doc.project(), actorId, std::string("Add a point to ") + spec.name,
                       [&](BlobTree& tr) -> Status {
                         BlobNode* n = tr.find(nodeId);
                         auto& list = std::get<ControlPoints>(n->params[i]);
                         // Continue the polyline by its last step.
                         glm::vec3 last = list.empty() ? glm::vec3(0.0f) : list.back().evaluate(t);
                         glm::vec3 step = list.size() >= 2 ? last - list[list.size() - 2].evaluate(t)
                                                           : glm::vec3(0.2f, 0.0f, 0.0f);
                         list.emplace_back(last + step);
                         return Status::success();
                       }),
          status);
    }
    noteWidget(std::string("inspector/blob/") + spec.name + "/add");
    ImGui::SameLine();
    if (ImGui::SmallButton("- point")) {
      if (int(pts.size()) <= spec.minCount) {
        status = {std::string(spec.name) + " needs at least " + std::to_string(spec.minCount) + " points", true};
      } else {
        run(doc,
            editBlobTree(doc.project(), actorId, std::string("Remove a point of ") + spec.name,
                         [&](BlobTree& tr) -> Status {
                           std::get<ControlPoints>(tr.find(nodeId)->params[i]).pop_back();
                           return Status::success();
                         }),
            status);
      }
    }
    ImGui::PopID();
  }
  ImGui::PopItemWidth();
  ImGui::Separator();
  ImGui::TextDisabled("%zu children (%d..%s)", node->children.size(), info.minChildren,
                      info.maxChildren < 0 ? "any" : std::to_string(info.maxChildren).c_str());
  ImGui::TextWrapped("Diamond: key at this frame. Fields of animated parameters (tinted) key this frame "
                     "when edited.");
}

void drawBlobActorInspector(Document& doc, const std::string& actorId, DragMerge& drag, StatusMessage& status) {
  const Actor* actor = doc.project().findActor(actorId);
  if (!actor || actor->kind != ActorKind::BlobTree) return;
  const BlobTree& tree = actor->blobTree;
  double end = cachedAnimationEndSec(tree, &doc, doc.revision());
  ImGui::TextDisabled("BlobTree");
  ImGui::SameLine(110.0f);
  ImGui::Text("%zu nodes, %s", tree.root.subtreeSize(),
              end > 0.0 ? ("animated over " + std::to_string(end).substr(0, 5) + " s").c_str() : "not animated");
  if (tree.threshold.isConstant()) {
    float thr = tree.threshold.evaluate(0.0);
    bool changed = ImGui::DragFloat("Threshold", &thr, 0.01f, 0.01f, 100.0f, "%.3f");
    noteWidget("inspector/blob/threshold");
    drag.begin(doc);
    if (changed) {
      BlobTree next = tree;
      next.threshold = FloatTrack(std::max(0.01f, thr));
      doc.execute(setBlobTreeCommand(doc.project(), actorId, std::move(next), "Set threshold of " + actor->name,
                                     "blobthreshold/" + actorId));
    }
    drag.end(doc);
  } else {
    ImGui::TextDisabled("Threshold");
    ImGui::SameLine(110.0f);
    ImGui::Text("%.3f (animated)", tree.threshold.evaluate(blobTreeTimeNow(doc, *actor)));
  }
  (void)status;
}

}  // namespace animorph
