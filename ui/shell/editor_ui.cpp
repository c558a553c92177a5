// EditorUI, the frame: requests from the app, the panels laid out and drawn, the viewport's overlay
// and splitters. Its other jobs are in their own files: editor_actions.cpp (menu and shortcut
// actions), editor_project.cpp (the project's life cycle and its prompts), editor_jobs.cpp
// (background jobs), editor_theme.cpp (colours and style).
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
#include "core/io/character_import.h"
#include "ui/shell/menu_bar.h"
#include "ui/shell/preferences_window.h"
#include "ui/shell/preview_controls.h"
#include "core/doc/project_commands.h"
#include "editor/selection_info.h"
#include "ui/timeline/transport.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {
const std::vector<FileFilter> kGlbFilters = {{"glTF binary (*.glb)", {".glb"}}};
// A sequence goes into a folder: the name typed is the folder's (made when missing).
const std::vector<FileFilter> kMp4Filters = {{"MPEG-4 video (*.mp4)", {".mp4"}}};
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
    if (isCharacterPath(p)) importCharacter(p, ctx);
    else refused.push_back(fileName(p));
  }
  if (!refused.empty()) {
    std::string names;
    for (const std::string& n : refused) names += (names.empty() ? "" : ", ") + n;
    setStatus("Cannot open " + names + ": drop an .animorph project or character files (.gltf, .glb, .fbx, .dae, .obj)", true);
  }
}

bool EditorUI::savePreferences() {
  Status s = animorph::savePreferences(st_.prefs, st_.prefsPath);
  if (!s) setStatus("Cannot save preferences: " + s.error(), true);
  return s.ok();
}

void EditorUI::setStatus(const std::string& text, bool error) { st_.status = {text, error, nowSec_}; }

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

// Autosave, asset reload and playback, before anything is drawn.
void EditorUI::housekeeping(EditorContext& ctx) {
  Document& d = doc(ctx);
  if (st_.prefs.autosaveIntervalSec > 0.0 && d.autosaveIfDue(ctx.nowSec, st_.prefs.autosaveIntervalSec) &&
      (st_.status.text.empty() || ctx.nowSec - st_.status.setSec >= kStatusHoldSec))
    setStatus("Autosaved to " + d.autosavePath());  // saved all the same; a recent report stays
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

// The panels laid out below the menu bar (its height from the last frame), the viewport and the
// editors over it; their actions go to actions.
void EditorUI::drawPanels(EditorContext& ctx, std::vector<Action>& actions) {
  const ImGuiIO& io = ImGui::GetIO();
  float statusHeight = ImGui::GetFrameHeight();
  glm::vec2 display(io.DisplaySize.x, io.DisplaySize.y);
  st_.layout = computeLayout(display, st_.menuBarHeight, statusHeight, layoutSizes(),
                             {st_.correspondence.visible, st_.curveEditor.visible});

  drawOutlinerPanel(st_.layout.outliner, doc(ctx), ctx.assets, st_.outliner, actions, st_.status);
  st_.inspector.morph.runtime = ctx.morphRuntime;
  st_.inspector.morph.hoveredChain = -1;  // set again while Chain matching is drawn
  st_.inspector.particles.busy = job_ != nullptr;
  drawInspectorPanel(st_.layout.inspector, doc(ctx), ctx.assets, st_.inspector, st_.drag, st_.status,
                     st_.standinTool);
  if (ParticleRequest r = std::exchange(st_.inspector.particles.request, ParticleRequest::None);
      r != ParticleRequest::None)
    startParticleJob(r, ctx);
  drawTimelinePanel(st_.layout.timeline, doc(ctx), st_.playback, keyFrames(ctx), st_.timeline, st_.drag, actions);
  drawStatusBar(st_.layout.statusBar, doc(ctx), ctx.stats, st_.status);
  drawViewport(ctx);
  drawCorrespondenceEditor(st_.layout.correspondence, doc(ctx), st_.correspondence, st_.inspector.morph, st_.status);
  // While the correspondence editor is open the curve editor shows the s curves,
  // unless a BlobTree node is selected (and no link is).
  st_.curveEditor.animorphosis = st_.correspondence.visible &&
                                 (st_.correspondence.selected || doc(ctx).selection.node < 0);
  st_.curveEditor.animorphosisLinkA = st_.correspondence.selected ? st_.correspondence.selected->nodeA : -1;
  st_.curveEditor.animorphosisLinkB = st_.correspondence.selected ? st_.correspondence.selected->nodeB : -1;
  drawCurveEditorPanel(st_.layout.curves, doc(ctx), st_.curveEditor, st_.status);
  drawWeightPaintPanel(st_.layout.viewport, doc(ctx), ctx.assets, st_.paint, st_.status);
  drawSplitters();
}

// Keyboard shortcuts: not while typing, not while a menu or dialog is open. Del and F belong to
// the curve editor or the correspondence editor while it has the focus.
void EditorUI::collectShortcuts(std::vector<Action>& actions) {
  if (ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel)) return;
  std::vector<Action> keys = pollShortcuts(ImGui::GetIO());
  for (Action a : keys)
    if ((!st_.curveEditor.focused || (a != Action::DeleteSelection && a != Action::FrameSelection)) &&
        !(st_.paint.active && a == Action::FrameSelection) &&  // F sets the brush radius while painting
        !(st_.correspondence.focused && (a == Action::DeleteSelection || a == Action::FrameSelection)))
      actions.push_back(a);
}

// The export and playblast dialogs: Browse opens the file browser for their output, Start runs them.
void EditorUI::drawOutputDialogs(EditorContext& ctx) {
  switch (drawExportDialog(doc(ctx), st_.exportDialog)) {
    case SettingsDialogChoice::Browse: {
      const bool gltf = st_.exportDialog.edit.format == ExportFormat::GltfAnimated;
      const fs::path out(st_.exportDialog.edit.output);
      st_.browser.open(FileBrowser::Mode::Save, gltf ? "Export to" : "Export into the folder",
                       gltf ? kGlbFilters : kFolderFilters,
                       out.has_parent_path() ? out.parent_path().string() : doc(ctx).baseDir(),
                       out.filename().string());
      st_.browserPurpose = BrowserPurpose::ExportOutput;
      break;
    }
    case SettingsDialogChoice::Start: startExport(ctx); break;
    case SettingsDialogChoice::Cancel:
    case SettingsDialogChoice::None: break;
  }
  switch (drawPlayblastDialog(doc(ctx), st_.playblastDialog)) {
    case SettingsDialogChoice::Browse: {
      const fs::path out(st_.playblastDialog.edit.output);
      st_.browser.open(FileBrowser::Mode::Save, "Playblast to", kMp4Filters,
                       out.has_parent_path() ? out.parent_path().string() : doc(ctx).baseDir(),
                       out.filename().string());
      st_.browserPurpose = BrowserPurpose::PlayblastOutput;
      break;
    }
    case SettingsDialogChoice::Start: startPlayblast(ctx); break;
    case SettingsDialogChoice::Cancel:
    case SettingsDialogChoice::None: break;
  }
}

void EditorUI::draw(EditorContext& ctx) {
  widgets_.clear();
  setActiveWidgetRects(&widgets_);
  out_.pick.reset();
  out_.screenshotPath.reset();
  out_.documentReplaced = false;
  nowSec_ = ctx.nowSec;
  if (st_.status.setSec < 0.0 && !st_.status.text.empty()) st_.status.setSec = nowSec_;  // set by a panel
  pollJob(ctx);  // a finished job's result first: this frame shows it
  housekeeping(ctx);

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
  drawPanels(ctx, actions);
  collectShortcuts(actions);
  if (menu.addNodeType) addNodeToSelection(*menu.addNodeType, ctx);
  if (!menu.openPath.empty()) guardUnsaved(PendingKind::OpenPath, menu.openPath, ctx);
  for (Action a : actions) dispatch(a, ctx);

  drawPrompts(ctx);
  drawOutputDialogs(ctx);
  if (!st_.standinTool.refitAllRequest.empty()) startRefitJob(ctx);
  if (st_.correspondence.bakeRequested) {
    st_.correspondence.bakeRequested = false;
    startBakeKeysJob(ctx);
  }
  if (st_.correspondence.autoMapRequested) {
    st_.correspondence.autoMapRequested = false;
    startAutoMapJob(ctx);
  }
  drawJob(ctx);
  drawCreateAnimorphosisPopup(doc(ctx), st_.createAnimorphosis, st_.correspondence, st_.status);
  if (st_.createAnimorphosis.createRequested) {
    st_.createAnimorphosis.createRequested = false;
    startCreateAnimorphosisJob(ctx);
  }
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
  out_.highlightChain = hoveredChainGuides(st_.inspector.morph,
                                           doc(ctx).project().timeline.currentTimeSec());
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
    ImGui::TextDisabled("File > Import Character... adds a character (glTF, FBX, Collada, OBJ); Create > New BlobTree Actor an implicit shape.");
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

LayoutSizes EditorUI::layoutSizes() const {
  const Preferences& p = st_.prefs;
  return {p.outlinerWidth, p.inspectorWidth, p.timelineHeight, p.editorsHeight, p.editorsSplit};
}

// Moves the size a splitter drags by the mouse's motion this frame.
void EditorUI::dragSplitter(int which, glm::vec2 delta) {
  Preferences& p = st_.prefs;
  switch (which) {
    case 0: p.outlinerWidth += delta.x; break;
    case 1: p.inspectorWidth -= delta.x; break;
    case 2: p.timelineHeight -= delta.y; break;
    case 3: p.editorsHeight -= delta.y; break;
    default: p.editorsSplit += delta.x / std::max(1.0f, st_.layout.editorsSplitter.size.x); break;
  }
}

// Stores the clamped sizes, so the file never holds a layout that does not fit, and saves them.
void EditorUI::storeLayoutSizes() {
  const ImGuiIO& io = ImGui::GetIO();
  const LayoutSizes c =
      clampLayout(layoutSizes(), {io.DisplaySize.x, io.DisplaySize.y}, st_.menuBarHeight, ImGui::GetFrameHeight());
  Preferences& p = st_.prefs;
  p.outlinerWidth = c.outlinerWidth, p.inspectorWidth = c.inspectorWidth, p.timelineHeight = c.timelineHeight;
  p.editorsHeight = c.editorsHeight, p.editorsSplit = c.editorsSplit;
  savePreferences();
}

void EditorUI::drawSplitters() {
  ImGuiIO& io = ImGui::GetIO();
  struct Splitter {
    const char* key;  // noted as splitter/KEY
    const LayoutRect* rect;
    bool vertical;  // a vertical bar dragged horizontally
  };
  const Splitter splitters[] = {{"outliner", &st_.layout.outlinerSplitter, true},
                                {"inspector", &st_.layout.inspectorSplitter, true},
                                {"timeline", &st_.layout.timelineSplitter, false},
                                {"editors", &st_.layout.editorsSplitter, false},
                                {"editors_divider", &st_.layout.editorsDivider, true}};
  for (int i = 0; i < int(std::size(splitters)); ++i) {
    const Splitter& s = splitters[i];
    const LayoutRect& r = *s.rect;
    if (r.size.x <= 0.0f || r.size.y <= 0.0f) continue;
    ImGui::SetNextWindowPos(ImVec2(r.min.x, r.min.y));
    ImGui::SetNextWindowSize(ImVec2(r.size.x, r.size.y));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.0f, 0.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
    ImGui::Begin((std::string("##split_") + s.key).c_str(), nullptr, kOverlayFlags);
    ImGui::PopStyleVar(3);
    ImGui::InvisibleButton("##handle", ImVec2(r.size.x, r.size.y));
    noteWidget(std::string("splitter/") + s.key);
    bool active = ImGui::IsItemActive();
    // The gap between panels (the window is cleared to the panels' colour: windowClearColor).
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(r.min.x, r.min.y), ImVec2(r.max().x, r.max().y),
                                              ImGui::GetColorU32(ImVec4(kGapColor[0], kGapColor[1], kGapColor[2], 1.0f)));
    if (active || ImGui::IsItemHovered()) {
      ImGui::SetMouseCursor(s.vertical ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
      ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(r.min.x, r.min.y), ImVec2(r.max().x, r.max().y),
                                                active ? IM_COL32(90, 160, 255, 200) : IM_COL32(90, 160, 255, 90));
    }
    if (active && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f))
      dragSplitter(i, {io.MouseDelta.x, io.MouseDelta.y});
    bool released = ImGui::IsItemDeactivated();
    ImGui::End();
    if (released) storeLayoutSizes();
  }
}

}  // namespace animorph
