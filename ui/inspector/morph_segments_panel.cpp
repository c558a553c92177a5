// The morph panel's user-controlled morphing section: the stand-in segments
// of source and target (by joint), and for the selected one its A / B end
// offsets and radius scale at the current morph progress u, each with a key
// button (a key at u, creating the segment's tracks on first use), and
// Remove tracks. The stand-in's rest geometry itself is edited elsewhere.
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "ui/inspector/blob_inspector.h"
#include "core/doc/morph_tracks.h"
#include "ui/inspector/morph_sections.h"
#include "editor/selection_info.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

template <class T>
bool keyedAt(const Track<T>& t, double u) {
  if (t.keys().size() < 2) return false;
  for (const auto& k : t.keys())
    if (std::abs(k.timeSec - u) < 1e-6) return true;
  return false;
}

std::string jointName(const Character* c, int node) {
  if (c && node >= 0 && node < int(c->nodes.size()) && !c->nodes[size_t(node)].name.empty())
    return c->nodes[size_t(node)].name;
  return "node " + std::to_string(node);
}

}  // namespace

void drawMorphSegments(Document& doc, AssetCache& assets, MorphPanelState& st, DragMerge& drag, StatusMessage& status) {
  const bool open = ImGui::CollapsingHeader("User-controlled morphing", ImGuiTreeNodeFlags_DefaultOpen);
  noteWidget("morph/segments");
  if (!open) return;
  const MorphSetup m = doc.project().morph;  // copy: commands below change the project
  const int frame = doc.project().timeline.currentFrame;
  const double u = morphProgressAt(m, frame);
  ImGui::TextWrapped("Key stand-in segments over the morph (B->C): align the skeletons, collapse one, grow the other.");

  // The segment list: source, then target.
  ImGui::BeginChild("##segments", ImVec2(0.0f, 150.0f), true);
  for (MorphSlot slot : {MorphSlot::Source, MorphSlot::Target}) {
    const ActorMorph* am = slotActor(m, slot);
    const Actor* actor = am ? doc.project().findActor(am->actorId) : nullptr;
    if (!am || !actor) continue;
    const Character* c = actorCharacter(doc, assets, *actor);
    const char* role = slot == MorphSlot::Source ? "source" : "target";
    ImGui::TextDisabled("%s: %s", slot == MorphSlot::Source ? "Source" : "Target", actor->name.c_str());
    for (size_t i = 0; i < am->standin.segments.size(); ++i) {
      const StandinSegment& seg = am->standin.segments[i];
      const bool keyed = findSegmentTracks(*am, int(i)) != nullptr;
      char label[160];
      std::snprintf(label, sizeof label, "%s %2zu  %s%s", keyed ? "*" : " ", i, jointName(c, seg.node).c_str(),
                    keyed ? "  (keyed)" : "");
      ImGui::PushID(role);
      ImGui::PushID(int(i));
      const bool selected = st.segmentSlot == int(slot) && st.segment == int(i);
      if (ImGui::Selectable(label, selected)) {
        st.segmentSlot = int(slot);
        st.segment = int(i);
      }
      ImGui::PopID();
      ImGui::PopID();
      noteWidget(std::string("morph/segment/") + role + "/" + std::to_string(i));
    }
  }
  ImGui::EndChild();

  const MorphSlot slot = st.segmentSlot == 1 ? MorphSlot::Target : MorphSlot::Source;
  const ActorMorph* am = slotActor(m, slot);
  if (!am || st.segment < 0 || st.segment >= int(am->standin.segments.size())) {
    ImGui::TextDisabled("Select a segment to key it.");
    return;
  }
  const int segment = st.segment;
  const SegmentTracks* tracks = findSegmentTracks(*am, segment);
  const StandinSegment& seg = am->standin.segments[size_t(segment)];
  ImGui::Text("%s segment %d: radius %.3f m", slot == MorphSlot::Source ? "Source" : "Target", segment, double(seg.radius));
  ImGui::Text("at u = %.3f (frame %d)", u, frame);
  if (frame < m.markers.b || frame > m.markers.c)
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "The current frame is outside B..C: u is clamped.");

  const std::string mergeBase = "morph/segment/" + std::to_string(int(slot)) + "/" + std::to_string(segment) + "/";
  ImGui::PushItemWidth(-110.0f);
  // One row: key button, then the field; typing keys the value at u too once the track is animated.
  auto row = [&](SegmentChannel ch, const char* label, const char* key, ParamSample value, bool keyedHere, bool animated) {
    ImGui::PushID(key);
    const bool keyNow = keyButton("##key", keyedHere, animated);
    noteWidget(std::string("morph/seg/") + key + "/key");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Key at the current morph progress u = %.3f", u);
    ImGui::SameLine();
    bool changed = false;
    if (auto* f = std::get_if<float>(&value)) changed = ImGui::DragFloat(label, f, 0.005f, 0.0f, 10.0f, "%.3f");
    else changed = ImGui::DragFloat3(label, &std::get<glm::vec3>(value).x, 0.002f, 0.0f, 0.0f, "%.3f");
    noteWidget(std::string("morph/seg/") + key);
    drag.begin(doc);
    if (changed || keyNow) {
      auto cmd = setSegmentTrackCommand(doc.project(), slot, segment, ch, u, value, keyNow,
                                        keyNow ? std::string() : mergeBase + key);
      if (cmd) doc.execute(std::move(*cmd));
      else status = {cmd.error(), true};
    }
    drag.end(doc);
    ImGui::PopID();
  };
  const glm::vec3 a = tracks ? tracks->aOffset.evaluate(u) : glm::vec3(0.0f);
  const glm::vec3 b = tracks ? tracks->bOffset.evaluate(u) : glm::vec3(0.0f);
  const float r = tracks ? tracks->radiusScale.evaluate(u) : 1.0f;
  row(SegmentChannel::AOffset, "A offset", "a_offset", a, tracks && keyedAt(tracks->aOffset, u), tracks != nullptr);
  row(SegmentChannel::BOffset, "B offset", "b_offset", b, tracks && keyedAt(tracks->bOffset, u), tracks != nullptr);
  row(SegmentChannel::RadiusScale, "Radius scale", "radius", r, tracks && keyedAt(tracks->radiusScale, u),
      tracks != nullptr);
  ImGui::PopItemWidth();
  ImGui::BeginDisabled(tracks == nullptr);
  if (ImGui::Button("Remove tracks")) {
    auto cmd = removeSegmentTracksCommand(doc.project(), slot, segment);
    if (cmd) doc.execute(std::move(*cmd));
    else status = {cmd.error(), true};
  }
  noteWidget("morph/seg/remove");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("offsets in the joint's space (m)");
}

}  // namespace animorph
