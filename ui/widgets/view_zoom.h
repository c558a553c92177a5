#pragma once
// Zooming and panning a view with the mouse, shared by the editors that have
// one (curve editor, correspondence editor): the wheel zooms around the mouse
// by a fixed step per notch, a middle drag moves the content with the mouse.
// A view is a span [lo, hi] of content units per axis, shown over a number of
// pixels.

namespace animorph {

// The factor a view's span is scaled by for a wheel movement (notches, up
// positive): below 1 (zoom in) for the wheel turned up.
double wheelSpanFactor(float wheelNotches);

// Scales [lo, hi] by factor around pivot (the content at pivot stays put).
void scaleSpanAround(double& lo, double& hi, double pivot, double factor);

// Moves [lo, hi], shown over spanPx pixels, so the content follows a mouse
// motion of deltaPx pixels. contentUp: content values grow against the pixel
// axis (a curve's values, up on the screen).
void panSpan(double& lo, double& hi, float deltaPx, float spanPx, bool contentUp = false);

}  // namespace animorph
