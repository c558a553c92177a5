#pragma once
// Everything the editor UI remembers between frames (no project data: that
// lives in the Document). A plain struct so tests and the app can inspect it.
#include <string>

#include "anim/playback.h"
#include "animorphosis/animorphosis_panel.h"
#include "curves/curve_editor_panel.h"
#include "viewport/gizmo.h"
#include "widgets/drag_merge.h"
#include "export/export_dialog.h"
#include "export/playblast_dialog.h"
#include "widgets/file_browser.h"
#include "inspector/inspector_panel.h"
#include "shell/layout.h"
#include "inspector/morph_create.h"
#include "view/camera.h"
#include "outliner/outliner_panel.h"
#include "viewport/standin_tool.h"
#include "shell/status_bar.h"
#include "timeline/timeline_panel.h"
#include "shell/prefs.h"
#include "viewport/viewport_input.h"
#include "viewport/viewport_mode.h"
#include "viewport/weight_paint_tool.h"

namespace animorph {

// An action waiting for the unsaved-changes question to be answered.
enum class PendingKind { None, New, Open, OpenPath, Quit };

// What a running file dialog is for.
enum class BrowserPurpose { None, OpenProject, SaveProjectAs, ImportCharacter, Screenshot, ExportOutput,
                            PlayblastOutput };

struct EditorState {
  Preferences prefs;  // layout sizes, camera scheme, recent files, autosave interval
  std::string prefsPath;
  OrbitCamera camera;
  Playback playback;
  ViewportInput viewportInput;
  LayoutRects layout;  // as computed for the last frame
  float menuBarHeight = 0.0f;

  // Windows.
  bool showPreferences = false;
  bool showShortcuts = false;
  bool showAbout = false;
  std::vector<std::string> demoProjects;  // Help > Demos (EditorUI::setDemoDir)

  // Panels.
  OutlinerState outliner;
  InspectorState inspector;
  TimelineState timeline;
  CurveEditorState curveEditor;
  CorrespondenceEditorState correspondence;
  CreateAnimorphosisState createAnimorphosis;
  CreateMorphState createMorph;
  GizmoState gizmo;
  ViewportMode viewportMode = ViewportMode::Object;
  StandinToolState standinTool;  // the selected stand-in segment and its handles
  WeightPaintState paint;  // Weight Paint mode
  DragMerge drag;

  // Dialogs.
  FileBrowser browser;
  ExportDialogState exportDialog;  // File > Export > Meshes and Volumes...
  PlayblastDialogState playblastDialog;  // File > Export > Playblast...
  BrowserPurpose browserPurpose = BrowserPurpose::None;
  PendingKind pending = PendingKind::None;
  std::string pendingPath;            // for PendingKind::OpenPath
  PendingKind afterSaveAs = PendingKind::None;  // continue this after Save As succeeds
  bool openUnsavedPrompt = false;     // request to open the modal next frame
  bool unsavedPromptOpen = false;
  std::string recoverPath;            // project whose newer autosave is offered
  bool openRecoverPrompt = false;
  std::string errorMessage;           // shown in the error modal
  bool openErrorPopup = false;

  StatusMessage status;
  double lastAssetRefreshSec = -1.0;
};

}  // namespace animorph
