#pragma once
// The morph's markers A..D on the timeline ruler: drawn as handles over the stages' coloured
// bands, hit-tested and moved (each move one command, merged while a drag is open).
#include <glm/glm.hpp>

#include "core/doc/document.h"

namespace animorph {

// Draws the markers A..D of the project's morph on a timeline ruler spanning
// [x0, x1] pixels for frames [viewStart, viewEnd], from y0 to y1.
void drawMorphMarkers(const Document& doc, float x0, float x1, float y0, float y1, double viewStart, double viewEnd);

// The marker (0..3 = A..D) whose handle on such a ruler is under pos, or -1.
int morphMarkerAt(const Document& doc, glm::vec2 pos, float x0, float x1, float y0, float y1, double viewStart,
                  double viewEnd);

// Moves marker index (0..3) to frame, kept between its neighbours and in the
// timeline range; a command merged while a drag is open.
void moveMorphMarker(Document& doc, int index, int frame);

}  // namespace animorph
