// EditorUI's actions: what a menu item or a shortcut asks for (Action), carried out on the document
// through commands.
#include "ui/shell/editor_ui.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <utility>

#include <imgui.h>

#include "core/doc/actor_commands.h"
#include "core/doc/blobtree_commands.h"
#include "core/doc/standin_commands.h"
#include "ui/outliner/node_type_menu.h"
#include "ui/shell/help_windows.h"
#include "core/io/gltf_import.h"
#include "ui/shell/menu_bar.h"
#include "ui/shell/preferences_window.h"
#include "ui/shell/preview_controls.h"
#include "core/doc/project_commands.h"
#include "editor/selection_info.h"
#include "ui/timeline/transport.h"
#include "ui/common/command_result.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {
const std::vector<FileFilter> kCharacterFilters = {
    {"Character (*.gltf, *.glb, *.fbx, *.dae, *.obj)", {".gltf", ".glb", ".fbx", ".dae", ".obj"}},
    {"glTF (*.gltf, *.glb)", {".gltf", ".glb"}},
    {"FBX (*.fbx)", {".fbx"}},
    {"Collada (*.dae)", {".dae"}},
    {"OBJ (*.obj)", {".obj"}},
    {"All files", {}}};
const std::vector<FileFilter> kPngFilters = {{"PNG image (*.png)", {".png"}}};
}  // namespace

// Delete: the selected stand-in segment (stand-in edit mode), BlobTree node, or actor.
void EditorUI::deleteSelection(EditorContext& ctx) {
  Document& d = doc(ctx);
  if (st_.viewportMode == ViewportMode::StandinEdit) {
    int seg = selectedStandinSegment(d);
    if (seg >= 0) {
      auto cmd = deleteStandinSegmentCommand(d.project(), d.selection.actorId, seg);
      if (cmd) {
        setStatus((*cmd)->label());
        d.execute(std::move(*cmd));
        d.selection.segment = -1;
      } else {
        setStatus(cmd.error(), true);
      }
      return;
    }
  }
  if (d.selection.actorId.empty()) return;
  const Actor* sel = d.project().findActor(d.selection.actorId);
  if (sel && sel->kind == ActorKind::BlobTree && d.selection.node >= 0) {
    auto cmd = deleteBlobNodeCommand(d.project(), d.selection.actorId, d.selection.node);
    if (executeOrReport(d, std::move(cmd), st_.status, /*announce=*/true)) d.selection.node = -1;
    return;
  }
  if (d.selection.node >= 0) {
    setStatus("Select the actor itself to delete it");
    return;
  }
  if (auto cmd = deleteActorCommand(d.project(), d.selection.actorId)) {
    setStatus(cmd->label());
    d.execute(std::move(cmd));
    d.selection = {};
  }
}

// Duplicate: the selected BlobTree node, the copy selected.
void EditorUI::duplicateSelection(EditorContext& ctx) {
  Document& d = doc(ctx);
  const Actor* sel = d.project().findActor(d.selection.actorId);
  if (!sel || sel->kind != ActorKind::BlobTree || d.selection.node < 0) {
    setStatus("Select a BlobTree node to duplicate it");
    return;
  }
  int copy = -1;
  auto cmd = duplicateBlobNodeCommand(d.project(), d.selection.actorId, d.selection.node, &copy);
  if (executeOrReport(d, std::move(cmd), st_.status, /*announce=*/true)) d.selection.node = copy;
}

// Create > New BlobTree Actor: added, selected and framed.
void EditorUI::addBlobActor(EditorContext& ctx) {
  Document& d = doc(ctx);
  Actor a = makeBlobTreeActor(d.project(), "Blob");
  a.loop = false;  // keys set past the last one must not wrap around while animating
  std::string id = a.id;
  setStatus("Added BlobTree actor " + a.name);
  d.execute(addActorCommand(std::move(a)));
  d.selection = {id, -1};
  frameSelection(ctx);
}

// Stand-in edit mode on or off (one viewport mode at a time).
void EditorUI::toggleStandinEdit(EditorContext& ctx) {
  Document& d = doc(ctx);
  st_.viewportMode = st_.viewportMode == ViewportMode::StandinEdit ? ViewportMode::Object : ViewportMode::StandinEdit;
  // One viewport mode at a time: entering stand-in editing leaves Weight Paint.
  if (st_.viewportMode == ViewportMode::StandinEdit && st_.paint.active) toggleWeightPaint(d, st_.paint, st_.status);
  if (st_.viewportMode == ViewportMode::StandinEdit && !d.project().morph.enabled())
    setStatus("Stand-in edit mode: the project has no morph, so no stand-ins to edit");
  else
    setStatus(std::string(viewportModeName(st_.viewportMode)) + " mode");
}

void EditorUI::dispatch(Action a, EditorContext& ctx) {
  Document& d = doc(ctx);
  switch (a) {
    case Action::New: guardUnsaved(PendingKind::New, {}, ctx); break;
    case Action::Open: guardUnsaved(PendingKind::Open, {}, ctx); break;
    case Action::Save: saveOrSaveAs(PendingKind::None, ctx); break;
    case Action::SaveAs: startSaveAs(PendingKind::None, ctx); break;
    case Action::Quit: guardUnsaved(PendingKind::Quit, {}, ctx); break;
    case Action::ImportCharacter:
      st_.browser.open(FileBrowser::Mode::Open, "Import Character", kCharacterFilters, d.baseDir());
      st_.browserPurpose = BrowserPurpose::ImportCharacter;
      break;
    case Action::Export: openExportDialog(d, st_.exportDialog); break;
    case Action::Playblast: openPlayblastDialog(d, st_.playblastDialog); break;
    case Action::SaveScreenshot:
      st_.browser.open(FileBrowser::Mode::Save, "Save Screenshot", kPngFilters, d.baseDir(),
                       fs::path(d.displayName()).stem().string() + ".png");
      st_.browserPurpose = BrowserPurpose::Screenshot;
      break;
    case Action::Undo: {
      std::string label = d.history().undoLabel();
      if (d.undo()) setStatus("Undid " + label);
      break;
    }
    case Action::Redo: {
      std::string label = d.history().redoLabel();
      if (d.redo()) setStatus("Redid " + label);
      break;
    }
    case Action::DeleteSelection: deleteSelection(ctx); break;
    case Action::DuplicateSelection: duplicateSelection(ctx); break;
    case Action::NewBlobActor: addBlobActor(ctx); break;
    case Action::ToggleCurveEditor: st_.curveEditor.visible = !st_.curveEditor.visible; break;
    case Action::ToggleCorrespondenceEditor: st_.correspondence.visible = !st_.correspondence.visible; break;
    case Action::CreateAnimorphosis: openCreateAnimorphosis(d, st_.createAnimorphosis); break;
    case Action::CreateMorph: openCreateMorph(d, st_.createMorph); break;
    case Action::BakeAnimorphosisKeys: startBakeKeysJob(ctx); break;
    case Action::ToggleGrid:
      d.execute(setViewOption(d.project(), &ViewOptions::showGrid, !d.project().view.showGrid, "Toggle grid"));
      break;
    case Action::ToggleSkeleton:
      d.execute(setViewOption(d.project(), &ViewOptions::showSkeleton, !d.project().view.showSkeleton,
                              "Toggle skeleton"));
      break;
    case Action::ToggleWireframe:
      d.execute(setViewOption(d.project(), &ViewOptions::wireframe, !d.project().view.wireframe, "Toggle wireframe"));
      break;
    case Action::ToggleAxes:
      d.execute(setViewOption(d.project(), &ViewOptions::showAxes, !d.project().view.showAxes, "Toggle axes"));
      break;
    case Action::ToggleStandins:
      d.execute(setViewOption(d.project(), &ViewOptions::showStandins, !d.project().view.showStandins,
                              "Toggle stand-ins"));
      break;
    case Action::ToggleStandinEdit: toggleStandinEdit(ctx); break;
    case Action::FrameSelection: frameSelection(ctx); break;
    case Action::PlayPause: togglePlayback(d, st_.playback); break;
    case Action::StepBack: stepFrames(d, st_.playback, -1); break;
    case Action::StepForward: stepFrames(d, st_.playback, +1); break;
    case Action::GoToStart: goToFrame(d, st_.playback, d.project().timeline.frameStart); break;
    case Action::GoToEnd: goToFrame(d, st_.playback, d.project().timeline.frameEnd); break;
    case Action::Preferences: st_.showPreferences = true; break;
    case Action::About: st_.showAbout = true; break;
    case Action::ShowShortcuts: st_.showShortcuts = true; break;
    case Action::ToggleWeightPaint:
      toggleWeightPaint(d, st_.paint, st_.status);
      if (st_.paint.active) st_.viewportMode = ViewportMode::Object;  // one viewport mode at a time
      break;
    case Action::ToggleWeightOverlay: st_.paint.overlayAlways = !st_.paint.overlayAlways; break;
    case Action::ImportWeights:
      if (weightPaintActor(d).empty() && d.project().morph.enabled()) d.selection = {d.project().morph.sourceActorId, -1};
      st_.paint.openImportPopup = true;
      break;
  }
}

void EditorUI::addNodeToSelection(NodeType type, EditorContext& ctx) {
  Document& d = doc(ctx);
  const Actor* sel = d.project().findActor(d.selection.actorId);
  if (!sel || sel->kind != ActorKind::BlobTree) {
    setStatus("Select a BlobTree actor or node first (Create > New BlobTree Actor makes one)", true);
    return;
  }
  std::string why;
  int parent = parentForNewNode(sel->blobTree, d.selection.node, &why);
  if (parent < 0) {
    setStatus(why, true);
    return;
  }
  int created = -1;
  auto cmd = addBlobNodeCommand(d.project(), d.selection.actorId, parent, type, &created);
  if (executeOrReport(d, std::move(cmd), st_.status, /*announce=*/true)) d.selection.node = created;
}

void EditorUI::frameSelection(EditorContext& ctx) {
  Document& d = doc(ctx);
  const Timeline& tl = d.project().timeline;
  double t = tl.currentTimeSec();
  Bounds b = ctx.selectionBounds ? ctx.selectionBounds(d, t) : selectionBounds(d, ctx.assets, t);
  if (b.empty()) {
    setStatus("Nothing to frame");
    return;
  }
  const LayoutRect& vp = st_.layout.viewport;
  st_.camera.frame(b, vp.size.y > 0.0f ? vp.size.x / vp.size.y : 1.0f);
}

}  // namespace animorph
