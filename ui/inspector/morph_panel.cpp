#include "ui/inspector/morph_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "ui/timeline/actor_timing.h"
#include "ui/inspector/blob_inspector.h"
#include "core/doc/morph_tracks.h"
#include "core/doc/project_commands.h"
#include "ui/inspector/morph_create.h"
#include "ui/inspector/morph_sections.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

void drawMorphSettings(Document& doc, AssetCache& assets, MorphPanelState& st, DragMerge& drag,
                       StatusMessage& status) {
  const MorphSetup m = doc.project().morph;  // copy: commands below change the project
  ImGui::TextUnformatted("Morph");
  ImGui::Separator();
  ImGui::Text("%s  ->  %s", m.sourceActorId.c_str(), m.targetActorId.c_str());
  drawMorphSides(doc, assets, status);
  ImGui::PushItemWidth(-90.0f);

  // Markers A..D in frames, kept in order: A <= B <= C <= D.
  MorphMarkers mk = m.markers;
  int v[4] = {mk.a, mk.b, mk.c, mk.d};
  bool changed = ImGui::DragInt4("Markers", v, 0.2f, doc.project().timeline.frameStart,
                                 doc.project().timeline.frameEnd);
  noteWidget("morph/markers");
  drag.begin(doc);
  if (changed) {
    for (int i = 1; i < 4; ++i) v[i] = std::max(v[i], v[i - 1]);
    MorphMarkers next{v[0], v[1], v[2], v[3]};
    if (!(next == mk)) doc.execute(setMorphField(doc.project(), &MorphSetup::markers, next, "Move morph markers", "morph/markers"));
  }
  drag.end(doc);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A: the source starts to collapse; B: implicit morph starts;\nC: the target starts to grow; D: the target plays");

  int method = static_cast<int>(m.method);
  const char* methods[] = {"Interpolation", "Space-time blending", "Skeleton correspondence"};
  if (ImGui::Combo("Method", &method, methods, 3))
    doc.execute(setMorphField(doc.project(), &MorphSetup::method, static_cast<MorphMethod>(method), "Set morph method"));
  noteWidget("morph/method");
  if (ImGui::IsItemHovered() && m.method == MorphMethod::SkeletonCorrespondence)
    ImGui::SetTooltip("The source's limbs move and resize into the target's along matched skeleton chains\n"
                      "(animorph-cli correspond prints the matching); needs a rig on both sides");
  if (m.method == MorphMethod::SkeletonCorrespondence) {
    int blend = m.correspondenceBlend == MorphMethod::SpaceTime ? 1 : 0;
    if (ImGui::Combo("Combined by", &blend, methods, 2))
      doc.execute(setMorphField(doc.project(), &MorphSetup::correspondenceBlend,
                                blend == 1 ? MorphMethod::SpaceTime : MorphMethod::Interpolation,
                                "Set correspondence blend"));
    noteWidget("morph/correspondence_blend");
  }

  if (m.method == MorphMethod::SpaceTime ||
      (m.method == MorphMethod::SkeletonCorrespondence && m.correspondenceBlend == MorphMethod::SpaceTime)) {
    SpaceTimeParams st = m.spaceTime;
    bool c = false;
    c |= ImGui::DragFloat("Time scale", &st.timeScale, 0.01f, 0.01f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a0 amount", &st.a0, 0.01f, 0.0f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a1 source", &st.a1, 0.05f, 0.01f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a2 target", &st.a2, 0.05f, 0.01f, 100.0f);
    drag.begin(doc);
    c |= ImGui::DragFloat("a3 time", &st.a3, 0.001f, 0.001f, 10.0f);
    drag.begin(doc);
    if (c && !(st == m.spaceTime))
      doc.execute(setMorphField(doc.project(), &MorphSetup::spaceTime, st, "Set space-time blending", "morph/spacetime"));
    drag.end(doc);
  }
  float shift = m.weightMapShift;
  bool c = ImGui::SliderFloat("Paint shift", &shift, 0.0f, 1.0f, "%.2f");
  drag.begin(doc);
  if (c) doc.execute(setMorphField(doc.project(), &MorphSetup::weightMapShift, shift, "Set weight-map shift", "morph/shift"));
  drag.end(doc);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("How much earlier painted vertices start their transition (fraction of the transition)");

  MorphCrossFade fade = m.crossFade;
  bool fc = ImGui::Checkbox("Cross-fade at B, C", &fade.enabled);
  noteWidget("morph/crossfade");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Around markers B and C, draw the mesh and the implicit surface dithered with\n"
                      "complementary opacity (hides the switch on coarse meshes)");
  if (fade.enabled) {
    fc |= ImGui::SliderInt("Fade width", &fade.widthFrames, 1, 24, "%d frames");
    drag.begin(doc);
  }
  if (fc && !(fade == m.crossFade))
    doc.execute(setMorphField(doc.project(), &MorphSetup::crossFade, fade, "Set morph cross-fade", "morph/crossfade"));
  drag.end(doc);
  ImGui::PopItemWidth();

  drawMorphCurveSettings(doc, drag, status);
  if (ImGui::CollapsingHeader("Clips")) {
    noteWidget("morph/clips");
    ImGui::PushItemWidth(-90.0f);
    for (const std::string* id : {&m.sourceActorId, &m.targetActorId}) {
      const Actor* a = doc.project().findActor(*id);
      if (!a) continue;
      const bool source = id == &m.sourceActorId;
      ImGui::TextDisabled("%s: %s", source ? "Source" : "Target", a->name.c_str());
      drawActorTiming(doc, Actor(*a), drag, source ? "morph/source" : "morph/target");
    }
    ImGui::PopItemWidth();
  } else {
    noteWidget("morph/clips");
  }
  if (m.method == MorphMethod::SkeletonCorrespondence) drawMorphChains(doc, st);
  drawMorphProjection(doc, st, drag);
  drawMorphSegments(doc, assets, st, drag, status);
}

namespace {

void run(Document& doc, Result<std::unique_ptr<Command>> cmd, StatusMessage& status) {
  if (cmd) doc.execute(std::move(*cmd));
  else status = {cmd.error(), true};
}

// True when track has two or more keys and one of them at time t.
bool keyedAt(const FloatTrack& track, double t) {
  if (track.keys().size() < 2) return false;
  for (const auto& k : track.keys())
    if (std::abs(k.timeSec - t) < 1e-6) return true;
  return false;
}

}  // namespace

void drawMorphCurveSettings(Document& doc, DragMerge& drag, StatusMessage& status) {
  if (!ImGui::CollapsingHeader("Curves", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const MorphSetup m = doc.project().morph;
  // Preset rows: one command sets the whole track.
  auto presets = [&](const char* label, const char* key, FloatTrack MorphSetup::*field) {
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(label);
    // Short captions so the row fits the inspector; the tooltip names the shape.
    static const char* kCaptions[4] = {"linear", "smooth", "in", "out"};
    static const char* kShapes[4] = {"linear: u", "smoothstep: 3u^2 - 2u^3", "ease-in: u^2", "ease-out: 1 - (1 - u)^2"};
    for (EasingPreset p : {EasingPreset::Linear, EasingPreset::Smoothstep, EasingPreset::EaseIn, EasingPreset::EaseOut}) {
      ImGui::SameLine();
      const std::string name = easingPresetName(p);
      ImGui::PushID(key);
      const bool clicked = ImGui::SmallButton(kCaptions[int(p)]);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kShapes[int(p)]);
      if (clicked) {
        FloatTrack t = easingPresetTrack(p);
        run(doc,
            editMorphTracks(doc.project(), std::string("Set ") + key + " to " + name,
                            [&](MorphSetup& next) -> Status {
                              next.*field = t;
                              return Status::success();
                            }),
            status);
      }
      ImGui::PopID();
      noteWidget(std::string("morph/") + key + "/" + name);
    }
  };
  presets("Easing", "easing", &MorphSetup::easing);  // alpha over a transition's progress (A->B, C->D)
  presets("Blend ", "blend", &MorphSetup::blend);    // w over the morph's progress (B->C)
  ImGui::TextDisabled("Edit them as curves: Ctrl+G.");

  // Solid noise: amplitude keyed over the morph's progress; frequency constant.
  const double u = morphProgressAt(m, doc.project().timeline.currentFrame);
  ImGui::PushItemWidth(-110.0f);
  float amp = m.noiseAmplitude.evaluate(u);
  const bool animated = m.noiseAmplitude.keys().size() >= 2;
  bool key = keyButton("##noise_key", keyedAt(m.noiseAmplitude, u), animated);
  noteWidget("morph/noise/key");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Key the noise amplitude at the current morph progress u = %.2f", u);
  ImGui::SameLine();
  bool changed = ImGui::DragFloat("Noise (m)", &amp, 0.0005f, 0.0f, 1.0f, "%.4f");
  noteWidget("morph/noise/amplitude");
  drag.begin(doc);
  if (changed || key) {
    const float v = std::max(0.0f, amp);
    run(doc,
        editMorphTracks(
            doc.project(), key ? "Key noise amplitude" : "Set noise amplitude",
            [&](MorphSetup& next) -> Status {
              setTrackValue(next.noiseAmplitude, u, v, key);
              return Status::success();
            },
            key ? std::string() : std::string("morph/noise")),
        status);
  }
  drag.end(doc);
  float freq = m.noiseFrequency;
  changed = ImGui::DragFloat("Frequency (1/m)", &freq, 0.05f, 0.01f, 1000.0f, "%.2f");
  noteWidget("morph/noise/frequency");
  drag.begin(doc);
  if (changed && freq > 0.0f)
    doc.execute(setMorphField(doc.project(), &MorphSetup::noiseFrequency, freq, "Set noise frequency", "morph/noise_freq"));
  drag.end(doc);
  ImGui::PopItemWidth();
}

}  // namespace animorph
