#pragma once
// A marker on the timeline ruler (the morph's A..D, the animorphosis interval):
// a vertical line and a small labelled flag above the stage bands, which a
// press on the ruler grabs.
#include <string>

#include <glm/glm.hpp>
#include <imgui.h>

namespace animorph {

// Pixel x of a (fractional) frame on a ruler spanning [x0, x1] for frames [viewStart, viewEnd].
inline float rulerX(double frame, float x0, float x1, double viewStart, double viewEnd) {
  return static_cast<float>(x0 + (frame - viewStart) * (x1 - x0) / (viewEnd - viewStart));
}

// Draws the marker at pixel x into the window's draw list (nothing when off
// [x0, x1]) and records its flag under widgetKey.
void drawRulerMarker(float x, float x0, float x1, float y0, float y1, const char* label, ImU32 color,
                     const std::string& widgetKey);

// True when pos is on the flag of the marker at pixel x of a ruler ending at y1.
bool rulerMarkerHit(glm::vec2 pos, float x, float y1);

}  // namespace animorph
