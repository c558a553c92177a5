#pragma once
// Everything the editor UI remembers between frames (no project data: that
// lives in the Document). A plain struct so tests and the app can inspect it.
#include <string>

#include "core/anim/playback.h"
#include "ui/animorphosis/animorphosis_panel.h"
#include "ui/curves/curve_editor_panel.h"
#include "ui/viewport/gizmo.h"
#include "ui/widgets/drag_merge.h"
#include "ui/export/export_dialog.h"
#include "ui/export/playblast_dialog.h"
#include "ui/widgets/file_browser.h"
#include "ui/inspector/inspector_panel.h"
#include "ui/common/layout.h"
#include "ui/inspector/morph_create.h"
#include "core/camera/camera.h"
#include "ui/outliner/outliner_panel.h"
#include "ui/viewport/standin_tool.h"
#include "ui/common/status_bar.h"
#include "ui/timeline/timeline_panel.h"
#include "ui/common/prefs.h"
#include "ui/viewport/viewport_input.h"
#include "ui/viewport/viewport_mode.h"
#include "ui/viewport/weight_paint_tool.h"

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
