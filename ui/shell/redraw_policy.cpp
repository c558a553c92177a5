#include "ui/shell/redraw_policy.h"

namespace animorph {

double RedrawPolicy::waitAfterFrame(const RedrawState& s) {
  if (s.input) settle_ = kSettleFrames;
  if (s.animating) return 0.0;
  if (settle_ > 0) {
    --settle_;
    return 0.0;
  }
  if (s.jobRunning) return kJobFrameSec;
  if (s.awaitingWork) return kWorkPollSec;
  return s.textInput ? kCaretTickSec : kIdleTickSec;
}

}  // namespace animorph
