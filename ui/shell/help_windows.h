#pragma once
// Help > Shortcuts (the shortcut table plus the viewport mouse bindings) and
// Help > About.
namespace animorph {

void drawShortcutsWindow(bool& open);
void drawAboutWindow(bool& open);

}  // namespace animorph
