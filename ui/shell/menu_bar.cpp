#include "ui/shell/menu_bar.h"

#include <filesystem>

#include <imgui.h>

#include "ui/outliner/node_type_menu.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {
namespace {
// BeginMenu with its header's rect recorded (once a menu is open ImGui's
// "last item" is the popup, so the rect is taken from the cursor instead).
bool beginMenu(const char* label, bool enabled = true) {
  ImVec2 pos = ImGui::GetCursorScreenPos();
  ImVec2 size(ImGui::CalcTextSize(label, nullptr, true).x, ImGui::GetFrameHeight());
  bool open = ImGui::BeginMenu(label, enabled);
  if (WidgetRects* r = activeWidgetRects()) r->set(std::string("menu/") + label, {{pos.x, pos.y}, {pos.x + size.x, pos.y + size.y}});
  return open;
}

// A menu's items: each adds its action to the result when chosen, and records its rectangle.
struct MenuItems {
  MenuResult& r;
  void item(const char* label, Action a, bool enabled = true, bool selected = false) {
    std::string hint = shortcutHint(a);
    if (ImGui::MenuItem(label, hint.empty() ? nullptr : hint.c_str(), selected, enabled)) r.actions.push_back(a);
    noteWidget(std::string("menu/") + label);
  }
};

void fileMenu(const Document& doc, const std::vector<std::string>& recentFiles, MenuItems& m) {
  m.item("New", Action::New);
  m.item("Open...", Action::Open);
  m.item("Save", Action::Save);
  m.item("Save As...", Action::SaveAs);
  ImGui::Separator();
  m.item("Import Character...", Action::ImportCharacter);
  m.item("Import Weights from Vertex Colour...", Action::ImportWeights, doc.project().morph.enabled());
  m.item("Save Screenshot...", Action::SaveScreenshot);
  // Export: the morph's frames as files, or a playblast movie of them.
  if (beginMenu("Export", doc.project().morph.enabled() || doc.project().animorphosis.enabled())) {
    m.item("Meshes and Volumes...", Action::Export);
    m.item("Playblast...", Action::Playblast);
    ImGui::EndMenu();
  }
  ImGui::Separator();
  bool recentOpen = beginMenu("Recent", !recentFiles.empty());
  if (recentOpen) {
    for (size_t i = 0; i < recentFiles.size(); ++i) {
      const std::string& path = recentFiles[i];
      std::string label = std::to_string(i + 1) + "  " + std::filesystem::path(path).filename().string();
      if (ImGui::MenuItem(label.c_str())) m.r.openPath = path;
      noteWidget("menu/Recent/" + std::to_string(i));
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", path.c_str());
    }
    ImGui::EndMenu();
  }
  ImGui::Separator();
  m.item("Quit", Action::Quit);
}

void editMenu(const Document& doc, MenuItems& m) {
  const UndoStack& h = doc.history();
  std::string undo = h.canUndo() ? "Undo " + h.undoLabel() : std::string("Undo");
  std::string redo = h.canRedo() ? "Redo " + h.redoLabel() : std::string("Redo");
  if (ImGui::MenuItem(undo.c_str(), shortcutHint(Action::Undo).c_str(), false, h.canUndo()))
    m.r.actions.push_back(Action::Undo);
  noteWidget("menu/Undo");
  if (ImGui::MenuItem(redo.c_str(), shortcutHint(Action::Redo).c_str(), false, h.canRedo()))
    m.r.actions.push_back(Action::Redo);
  noteWidget("menu/Redo");
  ImGui::Separator();
  const Actor* sel = doc.project().findActor(doc.selection.actorId);
  const bool blobNode = sel && sel->kind == ActorKind::BlobTree && doc.selection.node >= 0;
  m.item("Delete", Action::DeleteSelection, sel && (doc.selection.node < 0 || blobNode));
  m.item("Duplicate", Action::DuplicateSelection, blobNode);
}

void createMenu(const Document& doc, MenuItems& m) {
  m.item("New BlobTree Actor", Action::NewBlobActor);
  m.item("Morph...", Action::CreateMorph);
  m.item("Animorphosis...", Action::CreateAnimorphosis);
  ImGui::Separator();
  const Actor* sel = doc.project().findActor(doc.selection.actorId);
  const bool blob = sel && sel->kind == ActorKind::BlobTree;
  ImGui::TextDisabled(blob ? "Add node under the selection" : "Add node (select a BlobTree actor)");
  if (auto t = nodeTypeMenuItems("menu/Add/", blob)) m.r.addNodeType = *t;
}

void animorphosisMenu(const Document& doc, MenuItems& m) {
  m.item("New Animorphosis...", Action::CreateAnimorphosis);
  ImGui::Separator();
  m.item("Bake to Key-frame Actor", Action::BakeAnimorphosisKeys, doc.project().animorphosis.enabled());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Bake the animorphosis into a new, plain key-framed BlobTree actor (one undoable step).");
}

void viewMenu(const Document& doc, bool curveEditorShown, const WeightPaintState& paint, ViewportMode mode,
              bool correspondenceShown, MenuItems& m) {
  const ViewOptions& v = doc.project().view;
  m.item("Grid", Action::ToggleGrid, true, v.showGrid);
  m.item("Skeleton", Action::ToggleSkeleton, true, v.showSkeleton);
  m.item("Wireframe", Action::ToggleWireframe, true, v.wireframe);
  m.item("Axes", Action::ToggleAxes, true, v.showAxes);
  m.item("Stand-ins", Action::ToggleStandins, true, v.showStandins);
  ImGui::Separator();
  m.item("Frame Selection", Action::FrameSelection);
  ImGui::Separator();
  m.item("Curve Editor", Action::ToggleCurveEditor, true, curveEditorShown);
  m.item("Correspondence Editor", Action::ToggleCorrespondenceEditor, true, correspondenceShown);
  m.item("Weight Paint Mode", Action::ToggleWeightPaint, doc.project().morph.enabled(), paint.active);
  m.item("Stand-in Edit Mode", Action::ToggleStandinEdit, true, mode == ViewportMode::StandinEdit);
  m.item("Weight Overlay", Action::ToggleWeightOverlay, true, paint.overlayAlways);
  ImGui::Separator();
  m.item("Preferences...", Action::Preferences);
}

void helpMenu(const std::vector<std::string>& demos, MenuItems& m) {
  m.item("Shortcuts", Action::ShowShortcuts);
  m.item("About Animorph", Action::About);
  ImGui::Separator();
  if (beginMenu("Demos", !demos.empty())) {
    for (const std::string& path : demos) {
      const std::string name = std::filesystem::path(path).stem().string();
      if (ImGui::MenuItem(name.c_str())) m.r.openPath = path;
      noteWidget("menu/Demos/" + name);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", path.c_str());
    }
    ImGui::EndMenu();
  }
}

}  // namespace

MenuResult drawMenuBar(const Document& doc, const std::vector<std::string>& recentFiles, float& heightPx,
                       bool curveEditorShown, const WeightPaintState& paint, ViewportMode mode,
                       bool correspondenceShown, const std::vector<std::string>& demos) {
  MenuResult r;
  heightPx = 0.0f;
  if (!ImGui::BeginMainMenuBar()) return r;
  heightPx = ImGui::GetWindowSize().y;
  MenuItems m{r};
  if (beginMenu("File")) {
    fileMenu(doc, recentFiles, m);
    ImGui::EndMenu();
  }
  if (beginMenu("Edit")) {
    editMenu(doc, m);
    ImGui::EndMenu();
  }
  if (beginMenu("Create")) {
    createMenu(doc, m);
    ImGui::EndMenu();
  }
  if (beginMenu("Animorphosis")) {
    animorphosisMenu(doc, m);
    ImGui::EndMenu();
  }
  if (beginMenu("View")) {
    viewMenu(doc, curveEditorShown, paint, mode, correspondenceShown, m);
    ImGui::EndMenu();
  }
  if (beginMenu("Help")) {
    helpMenu(demos, m);
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
  return r;
}

}  // namespace animorph
