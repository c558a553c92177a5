#pragma once
// User preferences of the editor (not of a project; kept in ui/, the engine knows none of them): layout sizes, camera
// controls, recent files, autosave interval. Stored as JSON in
// $XDG_CONFIG_HOME/animorph/prefs.json (or ~/.config/animorph/prefs.json).
#include <string>
#include <vector>

#include "core/util/result.h"
#include "core/poly/preview_device.h"

namespace animorph {

// Which DCC's viewport mouse bindings are the primary ones.
enum class CameraScheme { Maya, Blender };

inline constexpr size_t kMaxRecentFiles = 8;

struct Preferences {
  float outlinerWidth = 260.0f;   // pixels; the UI clamps it to the window
  float inspectorWidth = 320.0f;  // pixels
  float timelineHeight = 140.0f;  // pixels
  float editorsHeight = 340.0f;   // pixels: the docked correspondence / curve editors below the viewport
  float editorsSplit = 0.5f;      // the correspondence editor's share of their width when both are open
  CameraScheme cameraScheme = CameraScheme::Maya;
  // Also accept the bindings of the other scheme where they do not conflict
  // with the primary one (Maya uses Alt, Blender the bare middle button).
  bool otherSchemeToo = true;
  std::vector<std::string> recentFiles;  // absolute paths, most recent first
  double autosaveIntervalSec = 60.0;     // 0 disables autosave
  // Implicit previews (BlobTrees, the morph's B->C stage): cells along the
  // longest side for the refined surface (shown once scrubbing stops) and for
  // the interactive one while things change. Both kMinPreviewResolution..kMaxPreviewResolution.
  int previewResolution = 128;
  int previewCoarseResolution = 96;
  PreviewDevice previewDevice = PreviewDevice::Auto;
  // BlobTrees of many point primitives (particles) drawn as spheres while scrubbing or playing,
  // their surface polygonised once the time holds still (editor/particle_view.h).
  bool particleView = true;
  bool operator==(const Preferences&) const = default;
};

// $XDG_CONFIG_HOME/animorph/prefs.json, else $HOME/.config/animorph/prefs.json.
std::string defaultPreferencesPath();

std::string preferencesToJson(const Preferences& p);
// Parses preferences; missing keys keep their defaults, unknown keys are
// ignored. The error names sourceName, the key and the reason.
Result<Preferences> preferencesFromJson(const std::string& text, const std::string& sourceName);

// Reads path. A missing file gives the defaults (first run); an unreadable or
// broken one gives an error (the caller keeps the defaults and tells the user).
Result<Preferences> loadPreferences(const std::string& path);
// Writes path atomically, creating its directory.
Status savePreferences(const Preferences& p, const std::string& path);

// Puts path first in the recent list (removing duplicates, keeping at most kMaxRecentFiles).
void addRecentFile(Preferences& p, const std::string& path);

}  // namespace animorph
