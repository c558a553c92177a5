#pragma once
// What the File > Export dialogs (Meshes and Volumes..., Playblast...) share: the state of a dialog
// that edits a copy of the project's last settings of its kind, its answer, opening it, and the
// refusal, buttons and end that follow each dialog's own fields.
#include <functional>
#include <string>

#include "core/project/project.h"

namespace animorph {

template <class Settings>
struct SettingsDialogState {
  bool openNext = false;  // open the modal on the next draw
  bool isOpen = false;
  Settings edit;          // what the dialog shows
  std::string error;      // why the dialog refused to start, shown in it
};

enum class SettingsDialogChoice { None, Browse, Start, Cancel };

// Starts editing saved (the project's last settings): with no output yet, defaultOutput; the
// frame range is the timeline's while useTimeline is set. The modal opens on the next draw.
template <class Settings>
void openSettingsDialog(const Project& p, const Settings& saved, const std::string& defaultOutput,
                        SettingsDialogState<Settings>& st) {
  st.edit = saved;
  if (st.edit.output.empty()) st.edit.output = defaultOutput;
  if (st.edit.useTimeline) {
    st.edit.first = p.timeline.frameStart;
    st.edit.last = p.timeline.frameEnd;
  }
  st.error.clear();
  st.openNext = true;
}

// After the dialog's fields (choice: what they answered, None or Browse): the refusal, the
// buttons (confirm, noted as prefix/confirmKey and prefix/cancel) and the modal's end. The
// confirm button answers Start only when problem() is "" (else that becomes the refusal).
SettingsDialogChoice finishSettingsDialog(SettingsDialogChoice choice, std::string& error, bool& isOpen,
                                          const std::string& prefix, const char* confirm, const char* confirmKey,
                                          const std::function<std::string()>& problem);

}  // namespace animorph
