#include "ui/timeline/transport.h"

#include <algorithm>

namespace animorph {

void goToFrame(Document& doc, Playback& playback, int frame) {
  const Timeline& tl = doc.project().timeline;
  frame = std::clamp(frame, tl.frameStart, std::max(tl.frameStart, tl.frameEnd));
  playback.seekFrame(frame, tl);
  doc.setCurrentFrame(frame);
}

void stepFrames(Document& doc, Playback& playback, int delta) {
  const Timeline& tl = doc.project().timeline;
  playback.pause();
  int start = tl.frameStart, end = std::max(tl.frameStart, tl.frameEnd);
  int f = tl.currentFrame + delta;
  if (tl.loop) {
    int len = end - start + 1;
    f = start + (((f - start) % len) + len) % len;
  }
  goToFrame(doc, playback, f);
}

void togglePlayback(Document& doc, Playback& playback) {
  const Timeline& tl = doc.project().timeline;
  playback.toggle(tl);
  doc.setCurrentFrame(playback.frame(tl));
}

}  // namespace animorph
