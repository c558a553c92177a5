#pragma once
// The editor's user interface: menu bar, outliner, inspector, timeline,
// status bar and the 3D viewport area, with file dialogs, unsaved-changes
// and autosave-recovery prompts, shortcuts, playback and viewport camera
// control. Pure ImGui over the Document; the app owns the window, the ImGui
// backends and the renderer, and reads EditorOutput after each draw().
//
// Per frame the app does: backend NewFrame, ImGui::NewFrame(), fill an
// EditorContext, EditorUI::draw(ctx), ImGui::Render(), draw the scene into
// output().viewport with output().camera, then the ImGui draw data on top.
// On the window's close button call requestQuit() and keep running until
// output().quit (the user may cancel on the unsaved-changes prompt).
//
// Implemented in five files: editor_ui.cpp (the frame), editor_actions.cpp (menu and shortcut
// actions), editor_project.cpp (open/save/quit and their prompts), editor_jobs.cpp (background
// jobs), editor_theme.cpp (colours and style).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/blobtree/node_type.h"
#include "ui/shell/editor_context.h"
#include "ui/shell/editor_state.h"
#include "core/util/background_job.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

class EditorUI {
 public:
  // Loads preferences from prefsPath; a broken file is reported in the
  // status bar and the defaults are used (and not written over until the
  // user changes something).
  explicit EditorUI(std::string prefsPath = defaultPreferencesPath());

  // Draws one frame and acts on the user's input. Call between
  // ImGui::NewFrame() and ImGui::Render().
  void draw(EditorContext& ctx);
  const EditorOutput& output() const { return out_; }

  // Asks to quit: the unsaved-changes prompt first if the document is dirty.
  void requestQuit();
  // Opens a project (command line, drag and drop), asking about unsaved changes first.
  void requestOpen(const std::string& path);
  // Files dropped on the window: a project (.animorph) opens (asking about unsaved changes
  // first); glTF files (.gltf, .glb) are imported as actors, each an undoable step.
  void requestDrop(std::vector<std::string> paths);
  // The folder whose .animorph projects Help > Demos lists (sorted by name); none when it has none.
  void setDemoDir(const std::string& dir);

  // The long operation running off the UI thread (opening a project, importing a glTF, an
  // export), or null. Its panel shows progress, the time left and Cancel; Esc cancels it too.
  // When it finishes, the next draw() applies its result to the Document (one undoable step).
  const BackgroundJob* runningJob() const { return job_.get(); }
  // What the job panel's Cancel and Esc do: asks the running job to stop (its work polls the flag)
  // and says so in the status bar; nothing without a job or once asked.
  void cancelJob();
  // Waits for the running job's work and applies its result now (headless tests drive the UI
  // frame by frame and want each frame's work done; the editor never blocks on a job).
  void finishJob(EditorContext& ctx);

  EditorState& state() { return st_; }
  const EditorState& state() const { return st_; }
  // Rectangles of named widgets drawn in the last frame (for automation).
  const WidgetRects& widgets() const { return widgets_; }

  // Writes the preferences file; failures go to the status bar. Returns success.
  bool savePreferences();
  // Applies the editor's colours and spacing to the current ImGui style.
  static void applyStyle();
  // The colour to clear the window to before the UI: the docked panels' background, which they
  // do not draw themselves (on a CPU device that was half the window shaded and blended again
  // every frame). Call after applyStyle().
  static void windowClearColor(float rgba[4]);

 private:
  Document& doc(EditorContext& ctx);
  void dispatch(Action a, EditorContext& ctx);
  void guardUnsaved(PendingKind kind, const std::string& path, EditorContext& ctx);
  void perform(PendingKind kind, const std::string& path, EditorContext& ctx);
  void openProjectPath(const std::string& path, EditorContext& ctx);
  void loadProject(const std::string& path, bool recover, EditorContext& ctx);
  // A glTF given to Open (or on the command line): a new untitled project with the character
  // imported; when it does not load, an error naming the path and the reason, the document kept.
  void openGltfAsNewProject(const std::string& path, EditorContext& ctx);
  void replaceDocument(std::unique_ptr<Document> d, EditorContext& ctx);
  // Saves to the document's file; an untitled document opens Save As and
  // continues with `after` once saved. Returns true if it saved now.
  bool saveOrSaveAs(PendingKind after, EditorContext& ctx);
  void startSaveAs(PendingKind after, EditorContext& ctx);
  void handleBrowserResult(const std::string& path, EditorContext& ctx);
  // Loads the glTF off the UI thread, then adds it as an actor (one undoable step).
  void importCharacter(const std::string& path, EditorContext& ctx);
  void addImportedActor(const std::string& path, EditorContext& ctx);
  // Runs work as the editor's background job; done runs on the UI thread with the work's status
  // (not for a cancelled job: the status bar says so). Refused, with a message, while another runs.
  // lateCancelDiscards: a Cancel that comes after the work returned but before the UI thread applied
  // its result discards the result too (for work with no effect outside it: the person asked for
  // nothing to change, and nothing does).
  using JobDone = std::function<void(EditorContext&, const Status&)>;
  bool startJob(std::string label, BackgroundJob::Work work, JobDone done, bool lateCancelDiscards = false);
  void pollJob(EditorContext& ctx);
  // Runs the inspector's Refit all (st_.standinTool.refitAllRequest) as the background job.
  void startRefitJob(EditorContext& ctx);
  // Animorphosis > Bake to Key-frame Actor: bakes the animorphosis off the UI thread, then adds
  // the key-frame BlobTree as a new actor (one undoable step) and reports the key counts.
  void startBakeKeysJob(EditorContext& ctx);
  // The correspondence editor's Auto-map: autoCorrespond on a copy of the project off the UI thread
  // (progress per level matched, Cancel between levels); its graph applied as one undoable command
  // when the animorphosis and its trees are still those it matched; a cancel changes nothing.
  void startAutoMapJob(EditorContext& ctx);
  // Create > Animorphosis... with automatic correspondence (st_.createAnimorphosis says what): the
  // animorphosis with its proposed graph built off the UI thread, applied as one undoable step when
  // the two actors are unchanged, then the correspondence editor opened; Cancel creates nothing.
  void startCreateAnimorphosisJob(EditorContext& ctx);
  void drawJob(EditorContext& ctx);
  void startExport(EditorContext& ctx);
  // File > Export > Playblast...: the dialog's settings become the project's (one undoable step),
  // then ctx.playblast runs on the background job (its own offscreen Vulkan device).
  void startPlayblast(EditorContext& ctx);
  // The Particles section's Simulate or Convert to particles, as a job; one undoable command.
  void startParticleJob(ParticleRequest request, EditorContext& ctx);
  // Convert to particles of a glTF character actor: a new BlobTree actor, selected.
  void startCharacterParticlesJob(EditorContext& ctx);
  void handleDrop(const std::vector<std::string>& paths, EditorContext& ctx);
  void frameSelection(EditorContext& ctx);
  void addNodeToSelection(NodeType type, EditorContext& ctx);
  // dispatch()'s longer actions: delete, duplicate, Create > New BlobTree Actor, stand-in edit mode.
  void deleteSelection(EditorContext& ctx);
  void duplicateSelection(EditorContext& ctx);
  void addBlobActor(EditorContext& ctx);
  void toggleStandinEdit(EditorContext& ctx);
  // draw()'s steps: autosave / asset reload / playback; the panels and editors (their actions
  // into actions); the keyboard shortcuts the focused editor does not take; the export and
  // playblast dialogs.
  void housekeeping(EditorContext& ctx);
  void drawPanels(EditorContext& ctx, std::vector<Action>& actions);
  void collectShortcuts(std::vector<Action>& actions);
  void drawOutputDialogs(EditorContext& ctx);
  void drawSplitters();
  // The panel sizes from the preferences; a splitter's drag (which: its index in drawSplitters);
  // the sizes clamped to the window and saved when a drag ends.
  LayoutSizes layoutSizes() const;
  void dragSplitter(int which, glm::vec2 delta);
  void storeLayoutSizes();
  void drawViewport(EditorContext& ctx);
  void drawPrompts(EditorContext& ctx);
  void showError(const std::string& message);
  void setStatus(const std::string& text, bool error = false);
  const std::vector<int>& keyFrames(EditorContext& ctx);

  EditorState st_;
  double nowSec_ = 0.0;  // the clock of the frame being drawn (stamps status messages)
  EditorOutput out_;
  std::unique_ptr<BackgroundJob> job_;
  JobDone jobDone_;
  bool jobLateCancelDiscards_ = false;
  WidgetRects widgets_;
  std::vector<std::pair<PendingKind, std::string>> external_;  // requestQuit/requestOpen
  std::vector<std::string> dropped_;                           // requestDrop
  // Cache of the selection's key frames.
  const Document* keysDoc_ = nullptr;
  uint64_t keysRevision_ = 0;
  Selection keysSelection_;
  std::vector<int> keys_;
};

}  // namespace animorph
