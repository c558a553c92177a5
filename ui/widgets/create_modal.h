#pragma once
// The frame shared by the Create > ... dialogs (Morph, Animorphosis) and File > Export...: a modal
// centred over the window, the last refusal in red, Create / Cancel buttons
// (Esc cancels), each noted in the widget map under a key prefix.
#include <string>

namespace animorph {

// Opens the popup id when openNext (and clears it), then begins it; false when it is not open.
bool beginCentredModal(const char* id, bool& openNext);

enum class ModalChoice { None, Create, Cancel };

// The refusal (when not empty, noted as keyPrefix + "/error"), a separator and the buttons, noted as
// keyPrefix + "/" + confirmKey and keyPrefix + "/cancel". File > Export... names its button Export.
ModalChoice createModalButtons(const std::string& error, const std::string& keyPrefix, const char* confirm = "Create",
                               const char* confirmKey = "create");

// Closes the popup when close (isOpen becomes false), then ends it.
void endCreateModal(bool close, bool& isOpen);

}  // namespace animorph
