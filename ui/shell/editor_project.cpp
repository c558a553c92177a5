// EditorUI's project life cycle: open, new, save, save as, quit, each guarded by the unsaved-changes
// prompt, the file browser's results, and the prompts themselves.
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
const std::vector<FileFilter> kProjectFilters = {{"Animorph project (*.animorph)", {".animorph"}},
                                                 {"All files", {}}};
// Open takes a character too: it becomes a new project with the character imported.
const std::vector<FileFilter> kOpenFilters = {
    {"Project or character (*.animorph, *.gltf, *.glb, *.fbx, *.dae, *.obj)",
     {".animorph", ".gltf", ".glb", ".fbx", ".dae", ".obj"}},
    {"Animorph project (*.animorph)", {".animorph"}},
    {"Character (*.gltf, *.glb, *.fbx, *.dae, *.obj)", {".gltf", ".glb", ".fbx", ".dae", ".obj"}},
    {"All files", {}}};

std::string fileName(const std::string& path) { return fs::path(path).filename().string(); }
}  // namespace

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
  if (isCharacterPath(path)) {
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
    case BrowserPurpose::ImportCharacter: importCharacter(path, ctx); break;
    case BrowserPurpose::ExportOutput:  // back to the dialog with the path chosen
      st_.exportDialog.edit.output = path;
      st_.exportDialog.openNext = true;
      break;
    case BrowserPurpose::PlayblastOutput:
      st_.playblastDialog.edit.output = path;
      st_.playblastDialog.openNext = true;
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
    // and Playblast dialogs come back as they were.
    if (st_.browserPurpose == BrowserPurpose::ExportOutput) st_.exportDialog.openNext = true;
    if (st_.browserPurpose == BrowserPurpose::PlayblastOutput) st_.playblastDialog.openNext = true;
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

}  // namespace animorph
