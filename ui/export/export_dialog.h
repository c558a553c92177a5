#pragma once
// File > Export...: the modal that sets what to export (format, frame range, resolution, output
// path; Browse... opens the in-app file browser) and starts it. It edits a copy of the project's
// last export settings; EditorUI stores them in the project (one undoable step) and runs the
// export as a background job when the user clicks Export.
#include <string>

#include "core/doc/document.h"
#include "ui/export/settings_dialog.h"

namespace animorph {

using ExportDialogState = SettingsDialogState<ExportSettings>;

// Opens the dialog with the project's last export settings; with no output yet, NAME.glb (or the
// folder NAME_frames for a sequence) beside the project.
void openExportDialog(const Document& doc, ExportDialogState& st);

// The settings' problem before anything runs ("" when none): no output path, last before first,
// resolution out of range.
std::string exportSettingsProblem(const Project& p, const ExportSettings& s);

// Draws the modal while open. Its Export button answers Start, only for settings without a problem.
SettingsDialogChoice drawExportDialog(const Document& doc, ExportDialogState& st);

}  // namespace animorph
