#include "ui/viewport/weight_paint_tool.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "core/doc/weight_map_command.h"
#include "core/scene/scene_frame.h"
#include "editor/selection_info.h"
#include "ui/widgets/widget_rects.h"
#include "ui/common/command_result.h"

namespace animorph {
namespace {

constexpr float kMinRadiusPx = 2.0f, kMaxRadiusPx = 600.0f;
constexpr float kRadiusKeyStep = 1.15f;  // [ and ] scale the radius by this

const char* const kModeLabels[] = {"Add", "Subtract", "Smooth", "Fill"};
const char* const kFalloffLabels[] = {"Smooth", "Linear", "Constant"};
const char* const kChannelLabels[] = {"Red", "Luminance", "Alpha"};

double currentTimeSec(const Document& doc) {
  const Timeline& tl = doc.project().timeline;
  return tl.currentTimeSec();
}

const std::vector<float>* documentMap(const Document& doc, const std::string& actorId) {
  const ActorMorph* am = doc.project().morph.findActor(actorId);
  return am ? &am->weightMap : nullptr;
}

// The painted actor's posed mesh at the current frame (cached).
std::shared_ptr<const PaintMesh> posedMesh(const Document& doc, AssetCache& assets, const std::string& actorId,
                                           WeightPaintState& st) {
  const int frame = doc.project().timeline.currentFrame;
  if (!st.mesh || st.meshDoc != &doc || st.meshRevision != doc.revision() || st.meshFrame != frame ||
      st.mesh->actorId != actorId) {
    SceneFrame sf = evaluateScene(doc.project(), doc.baseDir(), assets, currentTimeSec(doc));
    st.mesh = std::make_shared<const PaintMesh>(paintMeshFromFrame(sf, actorId));
    st.meshDoc = &doc;
    st.meshRevision = doc.revision();
    st.meshFrame = frame;
  }
  return st.mesh;
}

bool executeMap(Document& doc, const std::string& actorId, std::vector<float> map, const std::string& label,
                StatusMessage& status) {
  auto cmd = setWeightMapCommand(doc.project(), actorId, std::move(map), label);
  if (!executeOrReport(doc, std::move(cmd), status)) return false;
  status = {label + " (" + actorId + ")", false};
  return true;
}

void commitStroke(Document& doc, WeightPaintState& st, StatusMessage& status) {
  std::shared_ptr<WeightStroke> s = std::move(st.stroke);
  st.stroke.reset();
  if (!s || (s->verticesTouched() == 0 && st.brush.mode != BrushMode::Fill)) return;
  const std::vector<float>* before = documentMap(doc, s->mesh().actorId);
  if (before && *before == s->weights()) return;
  std::string label = std::string("Paint weights (") + brushModeName(st.brush.mode) + ")";
  if (executeMap(doc, s->mesh().actorId, s->weights(), label, status))
    status.text += ": " + std::to_string(s->verticesTouched()) + " vertices, " + std::to_string(s->dabCount()) + " dabs";
}

void drawImportControls(Document& doc, AssetCache& assets, const std::string& actorId, WeightPaintState& st,
                        StatusMessage& status, const char* keyPrefix) {
  int channel = static_cast<int>(st.importChannel);
  ImGui::SetNextItemWidth(110.0f);
  if (ImGui::Combo("##channel", &channel, kChannelLabels, 3)) st.importChannel = static_cast<ColorChannel>(channel);
  noteWidget(std::string(keyPrefix) + "channel");
  ImGui::SameLine();
  if (ImGui::Button("Import from vertex colour")) importWeightsFromColors(doc, assets, actorId, st.importChannel, status);
  noteWidget(std::string(keyPrefix) + "import");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Reads the weight map from the chosen channel of COLOR_0 in the actor's glTF file");
  static const char* const kTextureChannels[] = {"r", "g", "b", "alpha"};
  int texChannel = static_cast<int>(st.importTextureChannel);
  ImGui::SetNextItemWidth(110.0f);
  if (ImGui::Combo("##texture_channel", &texChannel, kTextureChannels, 4))
    st.importTextureChannel = static_cast<TextureChannel>(texChannel);
  noteWidget(std::string(keyPrefix) + "texture_channel");
  ImGui::SameLine();
  if (ImGui::Button("Import from texture"))
    importWeightsFromTexture(doc, assets, actorId, st.importTextureChannel, status);
  noteWidget(std::string(keyPrefix) + "import_texture");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Reads the weight map from the chosen channel of the actor's base colour texture, "
                      "sampled at each vertex's texture coordinates");
}

}  // namespace

std::string weightPaintActor(const Document& doc) {
  const MorphSetup& m = doc.project().morph;
  const std::string& id = doc.selection.actorId;
  if (id.empty() || !m.enabled()) return {};
  return id == m.sourceActorId || id == m.targetActorId ? id : std::string();
}

void toggleWeightPaint(Document& doc, WeightPaintState& st, StatusMessage& status) {
  if (st.active) {
    if (st.stroke) commitStroke(doc, st, status);
    st.active = false;
    st.adjustingRadius = false;
    status = {"Left Weight Paint mode", false};
    return;
  }
  if (!doc.project().morph.enabled()) {
    status = {"Weight painting needs a morph: its source and target actors have weight maps", true};
    return;
  }
  if (weightPaintActor(doc).empty()) doc.selection = Selection{doc.project().morph.sourceActorId, -1};
  st.active = true;
  status = {"Weight Paint mode: left drag paints " + doc.selection.actorId + "; [ ] or F set the radius", false};
}

bool importWeightsFromColors(Document& doc, AssetCache& assets, const std::string& actorId, ColorChannel channel,
                             StatusMessage& status) {
  const Actor* a = doc.project().findActor(actorId);
  const Character* c = a ? actorCharacter(doc, assets, *a) : nullptr;
  if (!c) {
    status = {"Import weights: actor '" + actorId + "' has no loaded glTF character", true};
    return false;
  }
  auto map = weightMapFromVertexColors(*c, channel);
  if (!map) {
    status = {"Import weights: " + map.error(), true};
    return false;
  }
  return executeMap(doc, actorId, std::move(*map),
                    std::string("Import weights from vertex colour (") + colorChannelName(channel) + ")", status);
}

bool importWeightsFromTexture(Document& doc, AssetCache& assets, const std::string& actorId, TextureChannel channel,
                              StatusMessage& status) {
  const Actor* a = doc.project().findActor(actorId);
  const Character* c = a ? actorCharacter(doc, assets, *a) : nullptr;
  if (!c) {
    status = {"Import weights: actor '" + actorId + "' has no loaded character", true};
    return false;
  }
  auto map = weightMapFromTexture(*c, channel);
  if (!map) {
    status = {"Import weights: " + map.error(), true};
    return false;
  }
  return executeMap(doc, actorId, std::move(*map),
                    std::string("Import weights from texture (") + textureChannelName(channel) + ")", status);
}

void drawWeightPaintPanel(const LayoutRect& viewport, Document& doc, AssetCache& assets, WeightPaintState& st,
                          StatusMessage& status) {
  const std::string actorId = weightPaintActor(doc);
  if (st.openImportPopup) {
    ImGui::OpenPopup("Import weights##paint");
    st.openImportPopup = false;
  }
  if (ImGui::BeginPopupModal("Import weights##paint", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (actorId.empty()) ImGui::TextDisabled("Select the morph's source or target actor first.");
    else ImGui::Text("Weight map of '%s' from its glTF vertex colours (COLOR_0), channel:", actorId.c_str());
    if (!actorId.empty()) drawImportControls(doc, assets, actorId, st, status, "paint/popup_");
    if (ImGui::Button("Close") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ImGui::CloseCurrentPopup();
    noteWidget("paint/popup_close");
    ImGui::EndPopup();
  }
  if (!st.active) return;

  ImGui::SetNextWindowPos(ImVec2(viewport.min.x + 8.0f, viewport.min.y + 30.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  constexpr ImGuiWindowFlags kFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                                      ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_AlwaysAutoResize |
                                      ImGuiWindowFlags_NoFocusOnAppearing;
  if (!ImGui::Begin("Weight Paint", nullptr, kFlags)) {
    ImGui::End();
    return;
  }
  noteWidget("paint/panel");
  const MorphSetup& m = doc.project().morph;
  for (const std::string* id : {&m.sourceActorId, &m.targetActorId}) {
    if (id != &m.sourceActorId) ImGui::SameLine();
    std::string label = (id == &m.sourceActorId ? "Source: " : "Target: ") + *id;
    if (ImGui::RadioButton(label.c_str(), actorId == *id)) doc.selection = Selection{*id, -1};
    noteWidget(id == &m.sourceActorId ? "paint/actor_source" : "paint/actor_target");
  }
  ImGui::PushItemWidth(150.0f);
  int mode = static_cast<int>(st.brush.mode);
  if (ImGui::Combo("Mode", &mode, kModeLabels, 4)) st.brush.mode = static_cast<BrushMode>(mode);
  noteWidget("paint/mode");
  int falloff = static_cast<int>(st.brush.falloff);
  if (ImGui::Combo("Falloff", &falloff, kFalloffLabels, 3)) st.brush.falloff = static_cast<BrushFalloff>(falloff);
  noteWidget("paint/falloff");
  ImGui::SliderFloat("Radius px", &st.brush.radiusPx, kMinRadiusPx, 300.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
  noteWidget("paint/radius");
  ImGui::SliderFloat(st.brush.mode == BrushMode::Fill ? "Value" : "Strength", &st.brush.strength, 0.0f, 1.0f, "%.2f");
  noteWidget("paint/strength");
  ImGui::Checkbox("X mirror", &st.brush.mirrorX);
  noteWidget("paint/mirror");
  ImGui::PopItemWidth();
  ImGui::BeginDisabled(actorId.empty());
  std::shared_ptr<const PaintMesh> mesh = actorId.empty() ? nullptr : posedMesh(doc, assets, actorId, st);
  if (ImGui::Button("Fill") && mesh)
    executeMap(doc, actorId, std::vector<float>(mesh->vertexCount(), std::clamp(st.brush.strength, 0.0f, 1.0f)),
               "Fill weights", status);
  noteWidget("paint/fill");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Sets every vertex to the Strength value");
  ImGui::SameLine();
  if (ImGui::Button("Clear")) executeMap(doc, actorId, {}, "Clear weights", status);
  noteWidget("paint/clear");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Removes the map: every vertex uses the whole transition");
  if (!actorId.empty()) drawImportControls(doc, assets, actorId, st, status, "paint/");
  ImGui::EndDisabled();
  if (actorId.empty()) {
    ImGui::TextDisabled("Select the morph's source or target actor.");
  } else {
    const std::vector<float>* map = documentMap(doc, actorId);
    size_t painted = 0;
    if (map)
      for (float w : *map) painted += w > 0.0f;
    if (!map || map->empty()) ImGui::TextDisabled("No weight map yet: painting creates one (0 everywhere).");
    else ImGui::TextDisabled("%zu of %zu vertices painted", painted, map->size());
  }
  ImGui::TextDisabled("LMB paint, [ ] or F radius, P leaves");
  ImGui::End();
}

bool updateWeightPaint(Document& doc, AssetCache& assets, const OrbitCamera& camera, const ViewportRect& viewport,
                       const PointerInput& in, WeightPaintState& st, StatusMessage& status, ImDrawList* draw) {
  st.cursor = in.pos;
  st.cursorInViewport = viewport.contains(in.pos) && !in.blockedByUi;
  if (!st.active) {
    st.stroke.reset();
    st.adjustingRadius = false;
    return false;
  }
  const std::string actorId = weightPaintActor(doc);
  const ImGuiIO& io = ImGui::GetIO();
  bool used = false;

  // Radius: [ and ], or F then a mouse move (Blender's radial control).
  const bool keysFree = !io.WantTextInput && !io.KeyCtrl && !io.KeyAlt && !st.stroke;
  if (keysFree && ImGui::IsKeyPressed(GLFW_KEY_LEFT_BRACKET))
    st.brush.radiusPx = std::max(kMinRadiusPx, st.brush.radiusPx / kRadiusKeyStep);
  if (keysFree && ImGui::IsKeyPressed(GLFW_KEY_RIGHT_BRACKET))
    st.brush.radiusPx = std::min(kMaxRadiusPx, st.brush.radiusPx * kRadiusKeyStep);
  if (st.adjustingRadius) {
    used = true;
    st.brush.radiusPx = std::clamp(glm::length(in.pos - st.adjustCentre), kMinRadiusPx, kMaxRadiusPx);
    if (in.pressed[1] || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
      st.brush.radiusPx = st.adjustStartRadius;
      st.adjustingRadius = false;
    } else if (in.pressed[0] || ImGui::IsKeyPressed(GLFW_KEY_F, false) ||
               ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter))) {
      st.adjustingRadius = false;
    }
  } else if (keysFree && st.cursorInViewport && ImGui::IsKeyPressed(GLFW_KEY_F, false)) {
    st.adjustingRadius = true;
    st.adjustStartRadius = st.brush.radiusPx;
    st.adjustCentre = in.pos - glm::vec2(st.brush.radiusPx, 0.0f);
    used = true;
  }

  // Strokes: left button without Alt (Alt+LMB stays the Maya orbit).
  const glm::vec2 local = in.pos - viewport.min;
  if (!used && !st.stroke && in.pressed[0] && !in.alt && st.cursorInViewport) {
    used = true;
    if (actorId.empty()) {
      status = {"Weight Paint: select the morph's source or target actor", true};
    } else if (auto mesh = posedMesh(doc, assets, actorId, st); mesh->vertexCount() == 0) {
      status = {"Weight Paint: '" + actorId + "' has no mesh at this frame", true};
    } else {
      const std::vector<float>* map = documentMap(doc, actorId);
      st.stroke = std::make_shared<WeightStroke>(*mesh, map ? *map : std::vector<float>{}, st.brush,
                                                 BrushView{camera, viewport.size});
      st.stroke->moveTo(local);
    }
  } else if (st.stroke) {
    used = true;
    st.stroke->moveTo(local);
  }
  if (st.stroke && !in.down[0]) commitStroke(doc, st, status);

  // The on-screen extent of the painted actor (for scripted GUI tests), and the brush circle.
  if (!actorId.empty()) {
    auto mesh = posedMesh(doc, assets, actorId, st);
    if (mesh->vertexCount() > 0) {
      glm::vec2 lo(1e30f), hi(-1e30f);
      for (const glm::vec3& p : mesh->positions) {
        glm::vec3 px = camera.worldToPixel(p, viewport.size);
        if (px.z < 0.0f || px.z > 1.0f) continue;
        lo = glm::min(lo, glm::vec2(px));
        hi = glm::max(hi, glm::vec2(px));
      }
      if (lo.x <= hi.x) noteWidgetRect("paint/target", viewport.min + lo, viewport.min + hi);
    }
  }
  if (draw && (st.cursorInViewport || st.adjustingRadius || st.stroke)) {
    const glm::vec2 c = st.adjustingRadius ? st.adjustCentre : in.pos;
    const float r = st.brush.radiusPx;
    const ImU32 ring = actorId.empty() ? IM_COL32(255, 120, 100, 220) : IM_COL32(255, 255, 255, 230);
    draw->AddCircle(ImVec2(c.x, c.y), r + 1.0f, IM_COL32(0, 0, 0, 160), 64, 1.0f);
    draw->AddCircle(ImVec2(c.x, c.y), r, ring, 64, 1.5f);
    draw->AddCircle(ImVec2(c.x, c.y), std::max(1.0f, r * std::clamp(st.brush.strength, 0.0f, 1.0f)),
                    IM_COL32(255, 255, 255, 90), 48, 1.0f);
    noteWidgetRect("paint/brush", c - glm::vec2(r), c + glm::vec2(r));
  }
  return used;
}

WeightOverlayRequest weightOverlayRequest(const Document& doc, const WeightPaintState& st) {
  WeightOverlayRequest r;
  if (!st.active && !st.overlayAlways) return r;
  r.actorId = weightPaintActor(doc);
  if (st.stroke && st.stroke->mesh().actorId == r.actorId) {
    r.weights = st.stroke->weights();
  } else if (!r.actorId.empty()) {
    if (const std::vector<float>* map = documentMap(doc, r.actorId)) r.weights = *map;
  }
  return r;
}

std::string weightPaintNote(const Document& doc, const WeightPaintState& st) {
  if (!st.active) return {};
  const std::string actorId = weightPaintActor(doc);
  char buf[200];
  std::snprintf(buf, sizeof buf, "weight paint: %s, %s, r %.0f px%s%s", actorId.empty() ? "(no morph actor selected)" : actorId.c_str(),
                brushModeName(st.brush.mode), st.brush.radiusPx, st.brush.mirrorX ? ", X mirror" : "",
                st.stroke ? ", painting" : "");
  return buf;
}

}  // namespace animorph
