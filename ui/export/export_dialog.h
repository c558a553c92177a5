#pragma once
// File > Export...: the modal that sets what to export (format, frame range, resolution, output
// path; Browse... opens the in-app file browser) and starts it. It edits a copy of the project's
// last export settings; EditorUI stores them in the project (one undoable step) and runs the
// export as a background job when the user clicks Export.
#include <string>

#include "doc/document.h"

namespace animorph {

struct ExportDialogState {
  bool openNext = false;  // open the modal on the next draw
  bool isOpen = false;
  ExportSettings edit;    // what the dialog shows
  std::string error;      // why Export was refused, shown in the dialog
};

enum class ExportDialogChoice { None, Browse, Export, Cancel };

// Opens the dialog with the project's last export settings; with no output yet, NAME.glb (or the
// folder NAME_frames for a sequence) beside the project.
void openExportDialog(const Document& doc, ExportDialogState& st);

// The settings' problem before anything runs ("" when none): no output path, last before first,
// resolution out of range.
std::string exportSettingsProblem(const Project& p, const ExportSettings& s);

// Draws the modal while open. Export is answered only for settings without a problem.
ExportDialogChoice drawExportDialog(const Document& doc, ExportDialogState& st);

}  // namespace animorph
