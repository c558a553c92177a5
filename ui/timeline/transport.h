#pragma once
// Moving the playhead: the timeline buttons, the ruler and the shortcuts all
// go through these so the Playback clock and the Document's current frame agree.
#include "core/anim/playback.h"
#include "core/doc/document.h"

namespace animorph {

// Sets the current frame (clamped to the range) and re-anchors playback there.
void goToFrame(Document& doc, Playback& playback, int frame);
// Steps by delta frames (pauses playback, as in Maya and Blender), wrapping
// around the range when the timeline loops.
void stepFrames(Document& doc, Playback& playback, int delta);
// Play/pause from the current frame.
void togglePlayback(Document& doc, Playback& playback);

}  // namespace animorph
