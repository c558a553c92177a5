#pragma once
// Edit > Preferences window: camera controls, autosave interval, panel
// sizes, recent files. Changes apply at once; the caller saves them.
#include "ui/common/prefs.h"

namespace animorph {

// Draws the window while open is true (its close button clears it). Returns
// true on a frame where prefs changed and should be written.
bool drawPreferencesWindow(bool& open, Preferences& prefs, const std::string& prefsPath);

}  // namespace animorph
