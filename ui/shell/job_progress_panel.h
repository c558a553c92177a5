#pragma once
// The running background job as the UI shows it: a small panel at the bottom of the viewport with
// the job's name and stage, a progress bar, the estimated time left and a Cancel button (Esc
// cancels too, EditorUI handles it). Drawn every frame while the job runs; the editor keeps
// drawing and taking input meanwhile.
#include "ui/common/layout.h"
#include "core/util/background_job.h"

namespace animorph {

// "Export: frame 12 (13 of 145)  42%  about 1 min 05 s left" as the panel shows it.
std::string jobProgressText(const BackgroundJob& job);

// Draws the panel over the bottom of viewport. Returns true when Cancel was clicked (widgets
// "job/progress" and "job/cancel").
bool drawJobProgressPanel(const LayoutRect& viewport, const BackgroundJob& job);

}  // namespace animorph
