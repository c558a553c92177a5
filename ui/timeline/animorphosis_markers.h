#pragma once
// The animorphosis interval on the timeline ruler: a band from t0 to t1 and a marker at each end,
// hit-tested and moved (each move one command, merged while a drag is open).
#include <glm/glm.hpp>

#include "core/doc/document.h"

namespace animorph {

// The interval [t0, t1] on a timeline ruler spanning [x0, x1] pixels for
// frames [viewStart, viewEnd], from y0 to y1: a band and two markers.
void drawAnimorphosisInterval(const Document& doc, float x0, float x1, float y0, float y1, double viewStart,
                              double viewEnd);
// The interval marker (0: start, 1: end) whose handle is under pos, or -1.
int animorphosisMarkerAt(const Document& doc, glm::vec2 pos, float x0, float x1, float y1, double viewStart,
                         double viewEnd);
// Moves a marker to frame (kept one frame from the other and inside the
// timeline range); a command merged while a drag is open.
void moveAnimorphosisMarker(Document& doc, int index, int frame);

}  // namespace animorph
