#pragma once
// File > Export > Playblast...: the modal that sets a playblast (frame range, polygonisation
// resolution, picture size, burn-in of the frame number and stage, the .mp4; Browse... opens the
// in-app file browser) and starts it. It edits a copy of the project's last playblast settings;
// EditorUI stores them in the project (one undoable step) and runs the playblast as a background
// job (export/playblast_job.h) when the user clicks Playblast.
#include <string>

#include "core/doc/document.h"
#include "ui/export/settings_dialog.h"

namespace animorph {

using PlayblastDialogState = SettingsDialogState<PlayblastSettings>;

// Opens the dialog with the project's last playblast settings; with no output yet, NAME.mp4
// beside the project.
void openPlayblastDialog(const Document& doc, PlayblastDialogState& st);

// The settings' problem before anything runs ("" when none): no output path, not an .mp4, last
// before first, picture size or resolution out of range, nothing to bake.
std::string playblastSettingsProblem(const Project& p, const PlayblastSettings& s);

// Draws the modal while open. Its Playblast button answers Start, only for settings without a problem.
SettingsDialogChoice drawPlayblastDialog(const Document& doc, PlayblastDialogState& st);

}  // namespace animorph
