#pragma once
// Controls of the implicit previews (BlobTree actors, the morph's B->C stage):
// where they are polygonised (Auto / GPU / CPU) and the interactive and refined
// resolutions. Shown in Edit > Preferences and behind the viewport header's
// "preview" button.
#include "ui/common/prefs.h"

namespace animorph {

// The device combo and the two resolution sliders, inline. Values change live;
// returns true once an edit is complete (the caller saves the preferences).
bool drawPreviewSettings(Preferences& prefs);

// The viewport header's button ("preview 96/128 auto") opening a popup with
// drawPreviewSettings. hovered: the mouse is on the button or the popup (the
// viewport must not take the click). Returns as drawPreviewSettings.
bool drawPreviewQuickControl(Preferences& prefs, bool& hovered);

}  // namespace animorph
