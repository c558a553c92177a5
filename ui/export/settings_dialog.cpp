#include "ui/export/settings_dialog.h"

#include "ui/widgets/create_modal.h"

namespace animorph {

SettingsDialogChoice finishSettingsDialog(SettingsDialogChoice choice, std::string& error, bool& isOpen,
                                          const std::string& prefix, const char* confirm, const char* confirmKey,
                                          const std::function<std::string()>& problem) {
  switch (createModalButtons(error, prefix, confirm, confirmKey)) {
    case ModalChoice::Create:
      error = problem();
      if (error.empty()) choice = SettingsDialogChoice::Start;
      break;
    case ModalChoice::Cancel: choice = SettingsDialogChoice::Cancel; break;
    case ModalChoice::None: break;
  }
  endCreateModal(choice != SettingsDialogChoice::None, isOpen);
  return choice;
}

}  // namespace animorph
