#include "ui/inspector/particles_panel.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <imgui.h>

#include "ui/widgets/widget_rects.h"

namespace animorph {

namespace {

// A float field; its widget is noted as inspector/particles/<key>.
void floatField(const char* label, const char* key, float& v, float speed, float lo, float hi, const char* fmt) {
  ImGui::DragFloat(label, &v, speed, lo, hi, fmt, ImGuiSliderFlags_AlwaysClamp);
  noteWidget(std::string("inspector/particles/") + key);
}

void vec3Field(const char* label, const char* key, glm::vec3& v, float speed) {
  ImGui::DragFloat3(label, &v.x, speed, 0.0f, 0.0f, "%.3f");
  noteWidget(std::string("inspector/particles/") + key);
}

// Explode and re-form: the shape to gather into (its own, or another BlobTree actor) and the button.
void drawReformControls(const Document& doc, const std::string& actorId, ParticlesPanelState& st) {
  ImGui::Separator();
  ImGui::TextUnformatted("Explode and re-form");
  const Actor* into = st.reformInto.empty() ? nullptr : doc.project().findActor(st.reformInto);
  if (!into || into->kind != ActorKind::BlobTree || into->id == actorId) {  // gone, or never set
    st.reformInto.clear();
    into = nullptr;
  }
  ImGui::SetNextItemWidth(-110.0f);
  if (ImGui::BeginCombo("Re-form into", into ? into->name.c_str() : "its own shape")) {
    if (ImGui::Selectable("its own shape", !into)) st.reformInto.clear();
    for (const Actor& a : doc.project().actors) {
      if (a.kind != ActorKind::BlobTree || a.id == actorId) continue;
      ImGui::PushID(a.id.c_str());
      if (ImGui::Selectable(a.name.c_str(), into == &a)) st.reformInto = a.id;
      noteWidget("inspector/particles/reform_into/" + a.id);
      ImGui::PopID();
    }
    ImGui::EndCombo();
  }
  noteWidget("inspector/particles/reform_into");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The shape the particles gather into: their own, or another BlobTree actor's volume\n"
                      "(each particle given one place so that paths do not cross)");
  ImGui::BeginDisabled(st.busy);
  if (ImGui::Button("Explode and re-form", ImVec2(-1.0f, 0.0f))) st.request = ParticleRequest::Reform;
  noteWidget("inspector/particles/reform");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The explosion above, then a vortex played backwards that gathers the particles into the\n"
                      "chosen shape: a new actor and the project's animorphosis (one undo step)");
  ImGui::EndDisabled();
}

}  // namespace

size_t countParticles(const BlobTree& tree) {
  size_t n = 0;
  forEachParticleNode(tree.root, [&](const BlobNode&) { ++n; });
  return n;
}

void resetParticleSettings(const BlobTree& tree, ParticlesPanelState& st) {
  double first = std::numeric_limits<double>::infinity(), last = -first;
  forEachParticleNode(tree.root, [&](const BlobNode& n) {
    const auto& keys = n.vec3Param("center").keys();
    if (keys.size() < 2) return;
    first = std::min(first, keys.front().timeSec);
    last = std::max(last, keys.back().timeSec);
  });
  st.settings = ParticleSettings{};
  st.bake = ParticleBakeOptions{};
  if (last > first) {
    st.bake.startSec = first;
    st.settings.durationSec = last - first;
  }
  TreeParticles tp = treeParticles(tree, st.bake.startSec);
  glm::vec3 centroid(0.0f);
  for (const glm::vec3& p : tp.set.position) centroid += p;
  if (!tp.set.position.empty()) centroid /= float(tp.set.position.size());
  st.reformInto.clear();
  st.settings.forces.explosion.centre = centroid;
  st.settings.forces.vortex.centre = centroid;
  if (!tp.set.position.empty()) st.convertCount = int(tp.set.position.size());
}

namespace {

// The count field and the Convert to particles button.
void drawConvertControls(ParticlesPanelState& st, const char* tooltip) {
  ImGui::BeginDisabled(st.busy);
  ImGui::SetNextItemWidth(110.0f);
  ImGui::InputInt("##count", &st.convertCount, 500, 5000);
  st.convertCount = std::clamp(st.convertCount, 1, 1'000'000);
  noteWidget("inspector/particles/count");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("How many particles fill the shape (to 1 %% above; up to 1,000,000)");
  ImGui::SameLine();
  if (ImGui::Button("Convert to particles")) st.request = ParticleRequest::Convert;
  noteWidget("inspector/particles/convert");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
  ImGui::EndDisabled();
}

// A character actor's section: what to fill (its stand-in or its posed mesh) and Convert.
void drawCharacterParticles(const Document& doc, const Actor& actor, ParticlesPanelState& st) {
  if (st.actorId != actor.id) {
    st.actorId = actor.id;
    st.reformInto.clear();
  }
  ImGui::Separator();
  const bool open = ImGui::CollapsingHeader("Particles", ImGuiTreeNodeFlags_DefaultOpen);
  noteWidget("inspector/particles/header");
  if (!open) return;
  const ActorMorph* am = doc.project().morph.findActor(actor.id);
  const bool hasStandin = am && !am->standin.segments.empty();
  ImGui::TextUnformatted("from:");
  ImGui::SameLine();
  if (ImGui::RadioButton("stand-in", st.convertFrom == ParticleSource::Standin)) st.convertFrom = ParticleSource::Standin;
  noteWidget("inspector/particles/from_standin");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(hasStandin ? "The morph's stand-in of this actor, posed at the current frame"
                                 : "No stand-in yet: one is fitted for the conversion (the actor keeps none)");
  ImGui::SameLine();
  if (ImGui::RadioButton("mesh", st.convertFrom == ParticleSource::Mesh)) st.convertFrom = ParticleSource::Mesh;
  noteWidget("inspector/particles/from_mesh");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The skinned mesh posed at the current frame (a mesh with holes is filled all the same,\n"
                      "its boundary edges reported)");
  drawConvertControls(st, "Fill the character's shape at the current frame with point primitives, as a new\n"
                          "BlobTree actor (the character stays; one undo step)");
}

}  // namespace

void drawParticlesSection(const Document& doc, const std::string& actorId, ParticlesPanelState& st) {
  const Actor* actor = doc.project().findActor(actorId);
  if (actor && actor->kind == ActorKind::Gltf) return drawCharacterParticles(doc, *actor, st);
  if (!actor || actor->kind != ActorKind::BlobTree) return;
  if (st.actorId != actorId) {
    st.actorId = actorId;
    resetParticleSettings(actor->blobTree, st);
  }
  ImGui::Separator();
  const bool open = ImGui::CollapsingHeader("Particles", ImGuiTreeNodeFlags_DefaultOpen);
  noteWidget("inspector/particles/header");
  if (!open) return;
  const size_t count = countParticles(actor->blobTree);
  if (count > 0) ImGui::Text("%zu particles (point primitives)", count);
  else ImGui::TextDisabled("No particles: convert the shape first.");

  drawConvertControls(st, "Fill the shape at the current frame with point primitives (one undo step)");
  if (count == 0) return;

  ParticleForces& f = st.settings.forces;
  ImGui::PushItemWidth(-110.0f);
  ImGui::TextUnformatted("Explosion");
  ImGui::Checkbox("Explode", &f.explosion.enabled);
  noteWidget("inspector/particles/explode");
  vec3Field("Centre", "explosion_centre", f.explosion.centre, 0.01f);
  floatField("Energy (J)", "energy", f.explosion.energy, 0.1f, 0.0f, 1e6f, "%.3g");
  floatField("Falloff (m)", "falloff", f.explosion.falloff, 0.01f, 1e-3f, 1e3f, "%.3g");
  ImGui::TextUnformatted("Forces");
  vec3Field("Gravity", "gravity", f.gravity, 0.05f);
  floatField("Drag (1/s)", "drag", f.drag, 0.01f, 0.0f, 100.0f, "%.3g");
  floatField("Noise (m/s2)", "noise", f.noise, 0.01f, 0.0f, 1000.0f, "%.3g");
  ImGui::Checkbox("Ground", &f.ground);
  noteWidget("inspector/particles/ground");
  if (f.ground) {
    floatField("Height (m)", "ground_height", f.groundHeight, 0.01f, -1e3f, 1e3f, "%.3f");
    floatField("Restitution", "restitution", f.restitution, 0.01f, 0.0f, 1.0f, "%.2f");
    floatField("Friction", "friction", f.friction, 0.01f, 0.0f, 1.0f, "%.2f");
  }
  ImGui::Checkbox("Vortex", &f.vortex.enabled);
  noteWidget("inspector/particles/vortex");
  if (f.vortex.enabled) {
    vec3Field("Vortex centre", "vortex_centre", f.vortex.centre, 0.01f);
    vec3Field("Axis", "vortex_axis", f.vortex.axis, 0.01f);
    floatField("Swirl (m/s)", "swirl", f.vortex.swirl, 0.05f, -100.0f, 100.0f, "%.3g");
    floatField("Core (m)", "core", f.vortex.radius, 0.01f, 1e-3f, 100.0f, "%.3g");
    floatField("Pull (m/s)", "pull", f.vortex.inward, 0.02f, -100.0f, 100.0f, "%.3g");
    floatField("Lift (m/s)", "lift", f.vortex.lift, 0.02f, -100.0f, 100.0f, "%.3g");
    floatField("Coupling (1/s)", "coupling", f.vortex.coupling, 0.05f, 0.0f, 1000.0f, "%.3g");
  }
  ImGui::TextUnformatted("Simulation");
  int seed = int(st.settings.seed);
  ImGui::InputInt("Seed", &seed);
  st.settings.seed = uint64_t(std::max(0, seed));
  noteWidget("inspector/particles/seed");
  float rate = float(st.settings.rateHz), start = float(st.bake.startSec), duration = float(st.settings.durationSec);
  floatField("Rate (Hz)", "rate", rate, 1.0f, 1.0f, 10000.0f, "%.0f");
  floatField("Start (s)", "start", start, 0.01f, -1e4f, 1e4f, "%.2f");
  floatField("Duration (s)", "duration", duration, 0.01f, 0.01f, 1e4f, "%.2f");
  st.settings.rateHz = rate;
  st.bake.startSec = start;
  st.settings.durationSec = duration;
  float tolMm = st.bake.tolerance * 1e3f;
  floatField("Tolerance (mm)", "tolerance", tolMm, 0.1f, 0.01f, 1000.0f, "%.2f");
  st.bake.tolerance = tolMm * 1e-3f;
  ImGui::Checkbox("Play backwards", &st.bake.reverse);
  noteWidget("inspector/particles/reverse");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Simulate from the positions at the end and write the animation backwards (it ends at rest)");
  ImGui::PopItemWidth();
  ImGui::BeginDisabled(st.busy);
  if (ImGui::Button("Simulate", ImVec2(-1.0f, 0.0f))) st.request = ParticleRequest::Simulate;
  noteWidget("inspector/particles/simulate");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Run the simulation and bake it into the particles' tracks (one undo step)");
  ImGui::EndDisabled();
  drawReformControls(doc, actorId, st);
}

}  // namespace animorph
