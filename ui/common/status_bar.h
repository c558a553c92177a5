#pragma once
// Status bar (bottom strip): fps, frame time, GPU device, document name
// (with * when it has unsaved changes) and the last message.
#include <string>

#include "core/doc/document.h"
#include "ui/common/layout.h"

namespace animorph {

// Frame statistics the app measures and hands to the UI.
struct FrameStats {
  float fps = 0.0f;
  float frameMs = 0.0f;
  std::string deviceName;
  std::string previewInfo;  // BlobTree preview state ("preview 128^3, 12 ms"), empty when none
};

struct StatusMessage {
  std::string text;
  bool error = false;
  double setSec = -1.0;  // the editor's clock when it was set
};

// How long a message stays before housekeeping (an autosave) may replace it: a job's report or
// an error is not overwritten by "Autosaved to ..." before the user could read it.
inline constexpr double kStatusHoldSec = 10.0;

// "name.animorph*" when dirty.
std::string documentTitle(const Document& doc);

void drawStatusBar(const LayoutRect& rect, const Document& doc, const FrameStats& stats, const StatusMessage& msg);

}  // namespace animorph
