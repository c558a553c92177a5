#include "core/export/playblast_job.h"

namespace animorph {

void playblastFrameRange(const Project& p, const PlayblastSettings& s, int& first, int& last) {
  first = s.useTimeline ? p.timeline.frameStart : s.first;
  last = s.useTimeline ? p.timeline.frameEnd : s.last;
}

}  // namespace animorph
