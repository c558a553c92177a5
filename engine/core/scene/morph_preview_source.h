#pragma once
// The morph's B->C stage at one time as a PreviewSource, so the editor
// polygonises it on the preview worker (poly/preview_polygonizer.h) or on the
// GPU (one program: morphImplicitField) instead of on the UI thread.
#include <memory>

#include "core/scene/morph_runtime.h"
#include "core/poly/preview_polygonizer.h"

namespace animorph {

// rt at scene time timeSec (expected inside B..C; elsewhere polygonize() gives
// that stage's mesh). progress >= 0: the implicit morph at that u whatever the
// stage (the cross-fade's surface just before B and after C). Two sources are
// the same when they share rt, the time and the progress.
std::shared_ptr<const PreviewSource> morphPreviewSource(std::shared_ptr<const MorphRuntime> rt, double timeSec,
                                                        double progress = -1.0);

// The stand-in core of the collapse (expand false) or the expansion at scene
// time timeSec and transition progress u (scene/standin_core.h): empty when
// it has melted away.
std::shared_ptr<const PreviewSource> standinCorePreviewSource(std::shared_ptr<const MorphRuntime> rt, double timeSec,
                                                              bool expand, double u);

}  // namespace animorph
