#include "shell/editor_ui.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <utility>

#include <imgui.h>

#include "doc/actor_commands.h"
#include "doc/blobtree_commands.h"
#include "doc/standin_commands.h"
#include "outliner/node_type_menu.h"
#include "shell/help_windows.h"
#include "io/gltf_import.h"
#include "shell/menu_bar.h"
#include "shell/preferences_window.h"
#include "shell/preview_controls.h"
#include "doc/project_commands.h"
#include "scene/selection_info.h"
#include "timeline/transport.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {
const std::vector<FileFilter> kProjectFilters = {{"Animorph project (*.animorph)", {".animorph"}},
                                                 {"All files", {}}};
// Open takes a glTF too: it becomes a new project with the character imported.
const std::vector<FileFilter> kOpenFilters = {
    {"Project or glTF (*.animorph, *.gltf, *.glb)", {".animorph", ".gltf", ".glb"}},
    {"Animorph project (*.animorph)", {".animorph"}},
    {"glTF (*.gltf, *.glb)", {".gltf", ".glb"}},
    {"All files", {}}};
const std::vector<FileFilter> kGltfFilters = {{"glTF (*.gltf, *.glb)", {".gltf", ".glb"}}, {"All files", {}}};
const std::vector<FileFilter> kPngFilters = {{"PNG image (*.png)", {".png"}}};
const std::vector<FileFilter> kGlbFilters = {{"glTF binary (*.glb)", {".glb"}}};
// A sequence goes into a folder: the name typed is the folder's (made when missing).
const std::vector<FileFilter> kFolderFilters = {{"Folder (type its name)", {}}};

constexpr float kGapColor[3] = {0.11f, 0.11f, 0.12f};  // between panels
constexpr ImGuiWindowFlags kOverlayFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                           ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground |
                                           ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoFocusOnAppearing |
                                           ImGuiWindowFlags_NoBringToFrontOnFocus |
                                           ImGuiWindowFlags_NoScrollWithMouse;

std::string fileName(const std::string& path) { return fs::path(path).filename().string(); }
}  // namespace

EditorUI::EditorUI(std::string prefsPath) {
  st_.prefsPath = std::move(prefsPath);
  auto loaded = loadPreferences(st_.prefsPath);
  if (loaded) {
    st_.prefs = std::move(*loaded);
  } else {
    setStatus("Preferences ignored: " + loaded.error(), true);
  }
  out_.camera = st_.camera;
}

void EditorUI::requestQuit() { external_.push_back({PendingKind::Quit, {}}); }
void EditorUI::requestOpen(const std::string& path) { external_.push_back({PendingKind::OpenPath, path}); }
void EditorUI::requestDrop(std::vector<std::string> paths) {
  dropped_.insert(dropped_.end(), std::make_move_iterator(paths.begin()), std::make_move_iterator(paths.end()));
}

void EditorUI::setDemoDir(const std::string& dir) {
  st_.demoProjects.clear();
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".animorph" && it->is_regular_file(ec)) st_.demoProjects.push_back(it->path().string());
  std::sort(st_.demoProjects.begin(), st_.demoProjects.end());
}

void EditorUI::handleDrop(const std::vector<std::string>& paths, EditorContext& ctx) {
  auto ext = [](const std::string& p) {
    std::string e = fs::path(p).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
  };
  auto project = std::find_if(paths.begin(), paths.end(), [&](const std::string& p) { return ext(p) == ".animorph"; });
  if (project != paths.end()) {  // a project replaces the document: the other files are not imported into it
    guardUnsaved(PendingKind::OpenPath, *project, ctx);
    if (paths.size() > 1) setStatus("Opened the dropped project " + fileName(*project) + "; the other dropped files were ignored");
    return;
  }
  std::vector<std::string> refused;
  for (const std::string& p : paths) {
    if (ext(p) == ".gltf" || ext(p) == ".glb") importGltf(p, ctx);
    else refused.push_back(fileName(p));
  }
  if (!refused.empty()) {
    std::string names;
    for (const std::string& n : refused) names += (names.empty() ? "" : ", ") + n;
    setStatus("Cannot open " + names + ": drop an .animorph project or .gltf / .glb files", true);
  }
}

bool EditorUI::savePreferences() {
  Status s = animorph::savePreferences(st_.prefs, st_.prefsPath);
  if (!s) setStatus("Cannot save preferences: " + s.error(), true);
  return s.ok();
}

void EditorUI::setStatus(const std::string& text, bool error) { st_.status = {text, error}; }

void EditorUI::showError(const std::string& message) {
  setStatus(message, true);
  st_.errorMessage = message;
  st_.openErrorPopup = true;
}

Document& EditorUI::doc(EditorContext& ctx) {
  if (!ctx.document) {
    ctx.document = std::make_unique<Document>();
    out_.documentReplaced = true;
  }
  return *ctx.document;
}

void EditorUI::draw(EditorContext& ctx) {
  widgets_.clear();
  setActiveWidgetRects(&widgets_);
  out_.pick.reset();
  out_.screenshotPath.reset();
  out_.documentReplaced = false;
  ImGuiIO& io = ImGui::GetIO();
  pollJob(ctx);  // a finished job's result first: this frame shows it

  // Housekeeping: autosave, asset reload, playback.
  {
    Document& d = doc(ctx);
    if (st_.prefs.autosaveIntervalSec > 0.0 && d.autosaveIfDue(ctx.nowSec, st_.prefs.autosaveIntervalSec))
      setStatus("Autosaved to " + d.autosavePath());
    if (ctx.nowSec - st_.lastAssetRefreshSec >= 1.0 || st_.lastAssetRefreshSec < 0.0) {
      st_.lastAssetRefreshSec = ctx.nowSec;
      if (int n = ctx.assets.refresh(); n > 0) setStatus("Reloaded " + std::to_string(n) + " changed asset(s)");
    }
    const Timeline& tl = d.project().timeline;
    if (st_.playback.playing()) {
      d.setCurrentFrame(st_.playback.advance(ctx.dtSec, tl));
    } else if (st_.playback.frame(tl) != std::clamp(tl.currentFrame, tl.frameStart, std::max(tl.frameStart, tl.frameEnd))) {
      st_.playback.seekFrame(tl.currentFrame, tl);
    }
  }

  std::vector<Action> actions;
  for (auto& [kind, path] : external_) guardUnsaved(kind, path, ctx);
  external_.clear();
  if (!dropped_.empty()) {
    std::vector<std::string> drop = std::move(dropped_);
    dropped_.clear();
    handleDrop(drop, ctx);
  }

  // Menu bar, then the panels laid out below it.
  MenuResult menu = drawMenuBar(doc(ctx), st_.prefs.recentFiles, st_.menuBarHeight, st_.curveEditor.visible, st_.paint,
                                st_.viewportMode, st_.correspondence.visible, st_.demoProjects);
  actions.insert(actions.end(), menu.actions.begin(), menu.actions.end());
  float statusHeight = ImGui::GetFrameHeight();
  LayoutSizes sizes{st_.prefs.outlinerWidth, st_.prefs.inspectorWidth, st_.prefs.timelineHeight};
  glm::vec2 display(io.DisplaySize.x, io.DisplaySize.y);
  st_.layout = computeLayout(display, st_.menuBarHeight, statusHeight, sizes);

  drawOutlinerPanel(st_.layout.outliner, doc(ctx), ctx.assets, st_.outliner, actions, st_.status);
  st_.inspector.morph.runtime = ctx.morphRuntime;
  st_.inspector.particles.busy = job_ != nullptr;
  drawInspectorPanel(st_.layout.inspector, doc(ctx), ctx.assets, st_.inspector, st_.drag, st_.status,
                     st_.standinTool);
  if (ParticleRequest r = std::exchange(st_.inspector.particles.request, ParticleRequest::None);
      r != ParticleRequest::None)
    startParticleJob(r, ctx);
  drawTimelinePanel(st_.layout.timeline, doc(ctx), st_.playback, keyFrames(ctx), st_.timeline, st_.drag, actions);
  drawStatusBar(st_.layout.statusBar, doc(ctx), ctx.stats, st_.status);
  drawViewport(ctx);
  drawCorrespondenceEditor(st_.layout.viewport, doc(ctx), st_.correspondence, st_.status);
  // While the correspondence editor is open the curve editor shows the s curves,
  // unless a BlobTree node is selected (and no link is).
  st_.curveEditor.animorphosis = st_.correspondence.visible &&
                                 (st_.correspondence.selected || doc(ctx).selection.node < 0);
  st_.curveEditor.animorphosisLinkA = st_.correspondence.selected ? st_.correspondence.selected->nodeA : -1;
  st_.curveEditor.animorphosisLinkB = st_.correspondence.selected ? st_.correspondence.selected->nodeB : -1;
  drawCurveEditorPanel(st_.layout.viewport, doc(ctx), st_.curveEditor, st_.status);
  drawWeightPaintPanel(st_.layout.viewport, doc(ctx), ctx.assets, st_.paint, st_.status);
  drawSplitters();

  // Keyboard shortcuts: not while typing, not while a menu or dialog is open.
  // Del and F belong to the curve editor or the correspondence editor while it has the focus.
  if (!ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel)) {
    std::vector<Action> keys = pollShortcuts(io);
    for (Action a : keys)
      if ((!st_.curveEditor.focused || (a != Action::DeleteSelection && a != Action::FrameSelection)) &&
          !(st_.paint.active && a == Action::FrameSelection) &&  // F sets the brush radius while painting
          !(st_.correspondence.focused && (a == Action::DeleteSelection || a == Action::FrameSelection)))
        actions.push_back(a);
  }
  if (menu.addNodeType) addNodeToSelection(*menu.addNodeType, ctx);

  if (!menu.openPath.empty()) guardUnsaved(PendingKind::OpenPath, menu.openPath, ctx);
  for (Action a : actions) dispatch(a, ctx);

  drawPrompts(ctx);
  switch (drawExportDialog(doc(ctx), st_.exportDialog)) {
    case ExportDialogChoice::Browse: {
      const bool gltf = st_.exportDialog.edit.format == ExportFormat::GltfAnimated;
      const fs::path out(st_.exportDialog.edit.output);
      st_.browser.open(FileBrowser::Mode::Save, gltf ? "Export to" : "Export into the folder",
                       gltf ? kGlbFilters : kFolderFilters,
                       out.has_parent_path() ? out.parent_path().string() : doc(ctx).baseDir(),
                       out.filename().string());
      st_.browserPurpose = BrowserPurpose::ExportOutput;
      break;
    }
    case ExportDialogChoice::Export: startExport(ctx); break;
    case ExportDialogChoice::Cancel:
    case ExportDialogChoice::None: break;
  }
  if (!st_.standinTool.refitAllRequest.empty()) startRefitJob(ctx);
  if (st_.correspondence.bakeRequested) {
    st_.correspondence.bakeRequested = false;
    startBakeKeysJob(ctx);
  }
  drawJob(ctx);
  drawCreateAnimorphosisPopup(doc(ctx), st_.createAnimorphosis, st_.correspondence, st_.status);
  drawCreateMorphPopup(doc(ctx), ctx.assets, st_.createMorph, st_.status);
  if (drawPreferencesWindow(st_.showPreferences, st_.prefs, st_.prefsPath)) savePreferences();
  drawShortcutsWindow(st_.showShortcuts);
  drawAboutWindow(st_.showAbout);

  st_.drag.endFrame(doc(ctx));
  out_.camera = st_.camera;
  out_.weightPaintMode = st_.paint.active;
  out_.jobRunning = job_ != nullptr;
  out_.weightOverlay = weightOverlayRequest(doc(ctx), st_.paint);
  out_.highlightBlobNode = st_.correspondence.visible ? st_.correspondence.hovered : Selection{};
  const LayoutRect& vp = st_.layout.viewport;
  out_.viewport = {vp.min, vp.size};
  setActiveWidgetRects(nullptr);
}

const std::vector<int>& EditorUI::keyFrames(EditorContext& ctx) {
  const Document& d = doc(ctx);
  if (keysDoc_ != &d || keysRevision_ != d.revision() || !(keysSelection_ == d.selection)) {
    keysDoc_ = &d;
    keysRevision_ = d.revision();
    keysSelection_ = d.selection;
    keys_ = selectionKeyFrames(d, ctx.assets);
  }
  return keys_;
}

void EditorUI::drawViewport(EditorContext& ctx) {
  const LayoutRect& r = st_.layout.viewport;
  ImGui::SetNextWindowPos(ImVec2(r.min.x, r.min.y));
  ImGui::SetNextWindowSize(ImVec2(std::max(r.size.x, 1.0f), std::max(r.size.y, 1.0f)));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));
  ImGui::Begin("##viewport", nullptr, kOverlayFlags);
  ImGui::PopStyleVar();
  bool hovered = ImGui::IsWindowHovered();
  const Document& d = doc(ctx);
  const std::string paintNote = weightPaintNote(d, st_.paint);
  ImGui::TextDisabled("%s camera  |  frame %d%s%s%s%s", st_.prefs.cameraScheme == CameraScheme::Maya ? "Maya" : "Blender",
                      d.project().timeline.currentFrame, ctx.viewportNote.empty() ? "" : "  |  ",
                      ctx.viewportNote.c_str(), paintNote.empty() ? "" : "  |  ", paintNote.c_str());
  if (!paintNote.empty()) noteWidget("viewport/paint_note");
  ImGui::SameLine();
  bool previewControlHovered = false;
  if (drawPreviewQuickControl(st_.prefs, previewControlHovered)) savePreferences();
  if (st_.viewportMode != ViewportMode::Object)
    ImGui::TextColored(ImVec4(0.5f, 0.9f, 1.0f, 1.0f), "%s mode", viewportModeName(st_.viewportMode));
  if (d.project().actors.empty())
    ImGui::TextDisabled("File > Import glTF... adds a character; Create > New BlobTree Actor an implicit shape.");
  ImGui::End();
  widgets_.set("viewport", {r.min, r.min + r.size});

  PointerInput in = pointerFromImGui(ImGui::GetIO(), !hovered || previewControlHovered);
  ViewportRect vr{r.min, r.size};
  // The gizmo goes first: while the mouse is on it, the camera and picking stay still.
  ImGui::Begin("##viewport", nullptr, kOverlayFlags);
  drawGizmo(doc(ctx), st_.camera, vr, in, st_.gizmo, st_.status, ImGui::GetWindowDrawList());
  const bool standinEdit = st_.viewportMode == ViewportMode::StandinEdit;
  if (standinEdit)
    drawStandinTool(doc(ctx), ctx.assets, st_.camera, vr, in, st_.standinTool, st_.status, ImGui::GetWindowDrawList());
  ImGui::End();
  if (st_.gizmo.hot() || (standinEdit && st_.standinTool.hot())) in.blockedByUi = true;
  updateWeightPaint(doc(ctx), ctx.assets, st_.camera, vr, in, st_.paint, st_.status, ImGui::GetForegroundDrawList());
  out_.pick = st_.viewportInput.update(in, vr, st_.prefs.cameraScheme, st_.prefs.otherSchemeToo, st_.camera);
  if (st_.paint.active) out_.pick.reset();  // a click paints instead of selecting
  // In the Stand-in edit mode a click on a capsule selects its segment instead of the mesh.
  if (standinEdit && out_.pick &&
      pickStandinClick(doc(ctx), ctx.assets, st_.camera, vr, out_.pick->windowPos, st_.standinTool))
    out_.pick.reset();
  if (st_.viewportInput.activeDrag() != CameraDrag::None)
    ImGui::SetMouseCursor(st_.viewportInput.activeDrag() == CameraDrag::Pan ? ImGuiMouseCursor_ResizeAll
                                                                             : ImGuiMouseCursor_Hand);
}

void EditorUI::drawSplitters() {
  ImGuiIO& io = ImGui::GetIO();
  struct Splitter {
    const char* id;
    const LayoutRect* rect;
    bool vertical;  // a vertical bar dragged horizontally
  };
  const Splitter splitters[] = {{"##split_outliner", &st_.layout.outlinerSplitter, true},
                                {"##split_inspector", &st_.layout.inspectorSplitter, true},
                                {"##split_timeline", &st_.layout.timelineSplitter, false}};
  for (const Splitter& s : splitters) {
    const LayoutRect& r = *s.rect;
    if (r.size.x <= 0.0f || r.size.y <= 0.0f) continue;
    ImGui::SetNextWindowPos(ImVec2(r.min.x, r.min.y));
    ImGui::SetNextWindowSize(ImVec2(r.size.x, r.size.y));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.0f, 0.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
    ImGui::Begin(s.id, nullptr, kOverlayFlags);
    ImGui::PopStyleVar(3);
    ImGui::InvisibleButton("##handle", ImVec2(r.size.x, r.size.y));
    std::string key = std::string("splitter/") + (s.id + 8);  // "outliner", "inspector", "timeline"
    noteWidget(key);
    bool active = ImGui::IsItemActive();
    // The gap between panels (the window is cleared to the panels' colour: windowClearColor).
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(r.min.x, r.min.y), ImVec2(r.max().x, r.max().y),
                                              ImGui::GetColorU32(ImVec4(kGapColor[0], kGapColor[1], kGapColor[2], 1.0f)));
    if (active || ImGui::IsItemHovered())
      ImGui::SetMouseCursor(s.vertical ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
    if (active || ImGui::IsItemHovered()) {
      ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(r.min.x, r.min.y), ImVec2(r.max().x, r.max().y),
                                                active ? IM_COL32(90, 160, 255, 200) : IM_COL32(90, 160, 255, 90));
    }
    if (active && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
      if (s.id == splitters[0].id) st_.prefs.outlinerWidth += io.MouseDelta.x;
      else if (s.id == splitters[1].id) st_.prefs.inspectorWidth -= io.MouseDelta.x;
      else st_.prefs.timelineHeight -= io.MouseDelta.y;
    }
    bool released = ImGui::IsItemDeactivated();
    ImGui::End();
    if (released) {
      // Store the clamped sizes so the file never holds a layout that does not fit.
      LayoutSizes c = clampLayout({st_.prefs.outlinerWidth, st_.prefs.inspectorWidth, st_.prefs.timelineHeight},
                                  {io.DisplaySize.x, io.DisplaySize.y}, st_.menuBarHeight, ImGui::GetFrameHeight());
      st_.prefs.outlinerWidth = c.outlinerWidth;
      st_.prefs.inspectorWidth = c.inspectorWidth;
      st_.prefs.timelineHeight = c.timelineHeight;
      savePreferences();
    }
  }
}

void EditorUI::dispatch(Action a, EditorContext& ctx) {
  Document& d = doc(ctx);
  switch (a) {
    case Action::New: guardUnsaved(PendingKind::New, {}, ctx); break;
    case Action::Open: guardUnsaved(PendingKind::Open, {}, ctx); break;
    case Action::Save: saveOrSaveAs(PendingKind::None, ctx); break;
    case Action::SaveAs: startSaveAs(PendingKind::None, ctx); break;
    case Action::Quit: guardUnsaved(PendingKind::Quit, {}, ctx); break;
    case Action::ImportGltf:
      st_.browser.open(FileBrowser::Mode::Open, "Import glTF", kGltfFilters, d.baseDir());
      st_.browserPurpose = BrowserPurpose::ImportGltf;
      break;
    case Action::Export: openExportDialog(d, st_.exportDialog); break;
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
    case Action::DeleteSelection: {
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
          break;
        }
      }
      if (d.selection.actorId.empty()) break;
      const Actor* sel = d.project().findActor(d.selection.actorId);
      if (sel && sel->kind == ActorKind::BlobTree && d.selection.node >= 0) {
        auto cmd = deleteBlobNodeCommand(d.project(), d.selection.actorId, d.selection.node);
        if (!cmd) {
          setStatus(cmd.error(), true);
          break;
        }
        setStatus((*cmd)->label());
        d.execute(std::move(*cmd));
        d.selection.node = -1;
        break;
      }
      if (d.selection.node >= 0) {
        setStatus("Select the actor itself to delete it");
        break;
      }
      if (auto cmd = deleteActorCommand(d.project(), d.selection.actorId)) {
        setStatus(cmd->label());
        d.execute(std::move(cmd));
        d.selection = {};
      }
      break;
    }
    case Action::DuplicateSelection: {
      const Actor* sel = d.project().findActor(d.selection.actorId);
      if (!sel || sel->kind != ActorKind::BlobTree || d.selection.node < 0) {
        setStatus("Select a BlobTree node to duplicate it");
        break;
      }
      int copy = -1;
      auto cmd = duplicateBlobNodeCommand(d.project(), d.selection.actorId, d.selection.node, &copy);
      if (!cmd) {
        setStatus(cmd.error(), true);
        break;
      }
      setStatus((*cmd)->label());
      d.execute(std::move(*cmd));
      d.selection.node = copy;
      break;
    }
    case Action::NewBlobActor: {
      Actor a = makeBlobTreeActor(d.project(), "Blob");
      a.loop = false;  // keys set past the last one must not wrap around while animating
      std::string id = a.id;
      setStatus("Added BlobTree actor " + a.name);
      d.execute(addActorCommand(std::move(a)));
      d.selection = {id, -1};
      frameSelection(ctx);
      break;
    }
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
    case Action::ToggleStandinEdit:
      st_.viewportMode = st_.viewportMode == ViewportMode::StandinEdit ? ViewportMode::Object : ViewportMode::StandinEdit;
      // One viewport mode at a time: entering stand-in editing leaves Weight Paint.
      if (st_.viewportMode == ViewportMode::StandinEdit && st_.paint.active) toggleWeightPaint(d, st_.paint, st_.status);
      if (st_.viewportMode == ViewportMode::StandinEdit && !d.project().morph.enabled())
        setStatus("Stand-in edit mode: the project has no morph, so no stand-ins to edit");
      else
        setStatus(std::string(viewportModeName(st_.viewportMode)) + " mode");
      break;
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
  if (!cmd) {
    setStatus(cmd.error(), true);
    return;
  }
  setStatus((*cmd)->label());
  d.execute(std::move(*cmd));
  d.selection.node = created;
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

void EditorUI::guardUnsaved(PendingKind kind, const std::string& path, EditorContext& ctx) {
  if (kind == PendingKind::None) return;
  if (doc(ctx).dirty()) {
    st_.pending = kind;
    st_.pendingPath = path;
    st_.openUnsavedPrompt = true;
    return;
  }
  perform(kind, path, ctx);
}

void EditorUI::perform(PendingKind kind, const std::string& path, EditorContext& ctx) {
  switch (kind) {
    case PendingKind::None: break;
    case PendingKind::New:
      replaceDocument(std::make_unique<Document>(), ctx);
      setStatus("New project");
      break;
    case PendingKind::Open: {
      std::string start = doc(ctx).path().empty()
                              ? (st_.prefs.recentFiles.empty() ? doc(ctx).baseDir()
                                                               : fs::path(st_.prefs.recentFiles[0]).parent_path().string())
                              : doc(ctx).baseDir();
      st_.browser.open(FileBrowser::Mode::Open, "Open Project", kOpenFilters, start);
      st_.browserPurpose = BrowserPurpose::OpenProject;
      break;
    }
    case PendingKind::OpenPath: openProjectPath(path, ctx); break;
    case PendingKind::Quit: out_.quit = true; break;
  }
}

void EditorUI::openProjectPath(const std::string& path, EditorContext& ctx) {
  if (isGltfPath(path)) {
    openGltfAsNewProject(path, ctx);
    return;
  }
  if (Document::hasNewerAutosave(path)) {
    st_.recoverPath = path;
    st_.openRecoverPrompt = true;
    return;
  }
  loadProject(path, false, ctx);
}

void EditorUI::replaceDocument(std::unique_ptr<Document> d, EditorContext& ctx) {
  if (ctx.document) ctx.document->endDrag();
  ctx.document = std::move(d);
  out_.documentReplaced = true;
  st_.playback.pause();
  const Timeline& tl = ctx.document->project().timeline;
  st_.playback.seekFrame(tl.currentFrame, tl);
  st_.outliner = {};
  st_.inspector = {};
  st_.timeline = {};
  st_.curveEditor.selection.clear();
  st_.curveEditor.sourceId.clear();
  st_.correspondence.selected.reset();
  st_.correspondence.treesKey.clear();
  st_.correspondence.dragSide = -1;
  st_.gizmo = {};
  st_.standinTool = {};
  st_.paint.stroke.reset();
  st_.paint.mesh.reset();
  keysDoc_ = nullptr;
  // Show the whole scene: frame every visible actor that loaded.
  Bounds b = selectionBounds(*ctx.document, ctx.assets, tl.currentTimeSec());
  if (!b.empty()) st_.camera.frame(b, st_.layout.viewport.size.y > 0.0f
                                          ? st_.layout.viewport.size.x / st_.layout.viewport.size.y
                                          : 1.0f);
}

bool EditorUI::saveOrSaveAs(PendingKind after, EditorContext& ctx) {
  Document& d = doc(ctx);
  if (d.path().empty()) {
    startSaveAs(after, ctx);
    return false;
  }
  Status s = d.save();
  if (!s) {
    showError("Save failed: " + s.error());
    return false;
  }
  addRecentFile(st_.prefs, d.path());
  savePreferences();
  setStatus("Saved " + d.path());
  return true;
}

void EditorUI::startSaveAs(PendingKind after, EditorContext& ctx) {
  Document& d = doc(ctx);
  std::string name = d.path().empty() ? d.project().name + ".animorph" : fileName(d.path());
  st_.browser.open(FileBrowser::Mode::Save, "Save Project As", kProjectFilters, d.baseDir(), name);
  st_.browserPurpose = BrowserPurpose::SaveProjectAs;
  st_.afterSaveAs = after;
}

void EditorUI::handleBrowserResult(const std::string& path, EditorContext& ctx) {
  BrowserPurpose purpose = st_.browserPurpose;
  st_.browserPurpose = BrowserPurpose::None;
  Document& d = doc(ctx);
  switch (purpose) {
    case BrowserPurpose::None: break;
    case BrowserPurpose::OpenProject: openProjectPath(path, ctx); break;
    case BrowserPurpose::SaveProjectAs: {
      Status s = d.saveAs(path);
      PendingKind after = st_.afterSaveAs;
      st_.afterSaveAs = PendingKind::None;
      if (!s) {
        showError("Save failed: " + s.error());
        break;
      }
      addRecentFile(st_.prefs, d.path());
      savePreferences();
      setStatus("Saved " + d.path());
      perform(after, st_.pendingPath, ctx);
      break;
    }
    case BrowserPurpose::ImportGltf: importGltf(path, ctx); break;
    case BrowserPurpose::ExportOutput:  // back to the dialog with the path chosen
      st_.exportDialog.edit.output = path;
      st_.exportDialog.openNext = true;
      break;
    case BrowserPurpose::Screenshot:
      out_.screenshotPath = path;
      setStatus("Screenshot: " + path);
      break;
  }
}

void EditorUI::drawPrompts(EditorContext& ctx) {
  if (auto chosen = st_.browser.draw()) handleBrowserResult(*chosen, ctx);
  if (!st_.browser.isOpen() && st_.browserPurpose != BrowserPurpose::None) {
    // Cancelled: a Save As that was to be followed by New/Open/Quit is dropped too; the Export
    // dialog comes back as it was.
    if (st_.browserPurpose == BrowserPurpose::ExportOutput) st_.exportDialog.openNext = true;
    st_.browserPurpose = BrowserPurpose::None;
    st_.afterSaveAs = PendingKind::None;
  }
  ImGuiIO& io = ImGui::GetIO();
  ImVec2 centre(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.4f);

  // Unsaved changes: Save / Don't Save / Cancel.
  if (st_.openUnsavedPrompt) {
    ImGui::OpenPopup("Unsaved changes##prompt");
    st_.openUnsavedPrompt = false;
  }
  ImGui::SetNextWindowPos(centre, ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  st_.unsavedPromptOpen = ImGui::BeginPopupModal("Unsaved changes##prompt", nullptr,
                                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
  if (st_.unsavedPromptOpen) {
    const char* what = st_.pending == PendingKind::Quit ? "quitting" : st_.pending == PendingKind::New ? "creating a new project" : "opening another project";
    ImGui::Text("Save the changes to %s before %s?", doc(ctx).displayName().c_str(), what);
    ImGui::TextDisabled("Your changes are lost if you don't save them.");
    ImGui::Separator();
    PendingKind kind = st_.pending;
    int choice = 0;
    if (ImGui::Button("Save", ImVec2(110.0f, 0.0f))) choice = 1;
    noteWidget("prompt/save");
    ImGui::SameLine();
    if (ImGui::Button("Don't Save", ImVec2(110.0f, 0.0f))) choice = 2;
    noteWidget("prompt/dont_save");
    ImGui::SameLine();
    if (ImGui::Button("Cancel", ImVec2(110.0f, 0.0f)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
      choice = 3;
    noteWidget("prompt/cancel");
    if (choice != 0) {
      ImGui::CloseCurrentPopup();
      st_.unsavedPromptOpen = false;
      st_.pending = PendingKind::None;
    }
    ImGui::EndPopup();
    if (choice == 1 && saveOrSaveAs(kind, ctx)) perform(kind, st_.pendingPath, ctx);
    if (choice == 2) perform(kind, st_.pendingPath, ctx);
    if (choice == 3) setStatus("Cancelled");
  }

  // A newer autosave exists: Recover / Discard.
  if (st_.openRecoverPrompt) {
    ImGui::OpenPopup("Recover autosave?##prompt");
    st_.openRecoverPrompt = false;
  }
  ImGui::SetNextWindowPos(centre, ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::BeginPopupModal("Recover autosave?##prompt", nullptr,
                             ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::Text("%s has an autosave newer than the file.", fileName(st_.recoverPath).c_str());
    ImGui::TextDisabled("Recover opens the autosave (save it to keep it); Discard deletes it.");
    int choice = 0;
    if (ImGui::Button("Recover", ImVec2(110.0f, 0.0f))) choice = 1;
    noteWidget("prompt/recover");
    ImGui::SameLine();
    if (ImGui::Button("Discard", ImVec2(110.0f, 0.0f))) choice = 2;
    noteWidget("prompt/discard");
    if (choice) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    if (choice == 2) {
      std::error_code ec;
      fs::remove(st_.recoverPath + ".autosave", ec);
    }
    if (choice) loadProject(st_.recoverPath, choice == 1, ctx);
  }

  // Errors.
  if (st_.openErrorPopup) {
    ImGui::OpenPopup("Error##popup");
    st_.openErrorPopup = false;
  }
  ImGui::SetNextWindowPos(centre, ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::BeginPopupModal("Error##popup", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::PushTextWrapPos(560.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", st_.errorMessage.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::Button("OK", ImVec2(110.0f, 0.0f)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
      ImGui::CloseCurrentPopup();
    noteWidget("error/ok");
    ImGui::EndPopup();
  }
}

void EditorUI::windowClearColor(float rgba[4]) {
  const ImVec4 c = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  rgba[0] = c.x;
  rgba[1] = c.y;
  rgba[2] = c.z;
  rgba[3] = 1.0f;
}

void EditorUI::applyStyle() {
  ImGuiStyle& s = ImGui::GetStyle();
  ImGui::StyleColorsDark(&s);
  s.WindowRounding = 0.0f;
  s.FrameRounding = 3.0f;
  s.GrabRounding = 3.0f;
  s.WindowBorderSize = 1.0f;
  s.ItemSpacing = ImVec2(6.0f, 4.0f);
  s.Colors[ImGuiCol_WindowBg] = ImVec4(0.16f, 0.16f, 0.18f, 1.0f);
  s.Colors[ImGuiCol_TitleBgActive] = ImVec4(0.20f, 0.22f, 0.27f, 1.0f);
}

}  // namespace animorph
