// The animorphosis interval on the timeline ruler: a band from t0 to t1 and a
// marker at each end, dragged like the morph's markers.
#include <algorithm>
#include <cmath>

#include "ui/timeline/animorphosis_markers.h"
#include "core/doc/animorphosis_commands.h"
#include "ui/timeline/ruler_marker.h"

namespace animorph {

namespace {
constexpr ImU32 kIntervalColor = IM_COL32(80, 200, 170, 230);

// Start and end of the interval in (fractional) frames.
void intervalFrames(const Project& p, double& start, double& end) {
  const double fps = p.timeline.fps > 0.0 ? p.timeline.fps : 24.0;
  start = p.animorphosis.startSec * fps;
  end = p.animorphosis.endSec * fps;
}
}  // namespace

void drawAnimorphosisInterval(const Document& doc, float x0, float x1, float y0, float y1, double viewStart,
                              double viewEnd) {
  const Project& p = doc.project();
  if (!p.animorphosis.enabled() || viewEnd <= viewStart) return;
  double start = 0.0, end = 0.0;
  intervalFrames(p, start, end);
  const float xs = rulerX(start, x0, x1, viewStart, viewEnd), xe = rulerX(end, x0, x1, viewStart, viewEnd);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  if (xe > x0 && xs < x1)
    dl->AddRectFilled(ImVec2(std::max(x0, xs), y1 - 6.0f), ImVec2(std::min(x1, xe), y1), IM_COL32(80, 200, 170, 120));
  drawRulerMarker(xs, x0, x1, y0, y1, "0", kIntervalColor, "timeline/animorphosis/start");
  drawRulerMarker(xe, x0, x1, y0, y1, "1", kIntervalColor, "timeline/animorphosis/end");
}

int animorphosisMarkerAt(const Document& doc, glm::vec2 pos, float x0, float x1, float y1, double viewStart,
                         double viewEnd) {
  const Project& p = doc.project();
  if (!p.animorphosis.enabled() || viewEnd <= viewStart) return -1;
  double start = 0.0, end = 0.0;
  intervalFrames(p, start, end);
  // The end first: it is drawn on top.
  if (rulerMarkerHit(pos, rulerX(end, x0, x1, viewStart, viewEnd), y1)) return 1;
  if (rulerMarkerHit(pos, rulerX(start, x0, x1, viewStart, viewEnd), y1)) return 0;
  return -1;
}

void moveAnimorphosisMarker(Document& doc, int index, int frame) {
  const Project& p = doc.project();
  const Timeline& tl = p.timeline;
  const double fps = tl.fps > 0.0 ? tl.fps : 24.0;
  double start = 0.0, end = 0.0;
  intervalFrames(p, start, end);
  if (index == 0) {
    const int hi = int(std::ceil(end)) - 1;
    frame = std::clamp(frame, std::min(tl.frameStart, hi), hi);
    if (std::abs(frame - start) < 1e-9) return;
    start = frame;
  } else {
    const int lo = int(std::floor(start)) + 1;
    frame = std::clamp(frame, lo, std::max(lo, tl.frameEnd));
    if (std::abs(frame - end) < 1e-9) return;
    end = frame;
  }
  auto cmd = setAnimorphosisIntervalCommand(p, start / fps, end / fps, "animorphosis/interval");
  if (cmd) doc.execute(std::move(*cmd));
}

}  // namespace animorph
