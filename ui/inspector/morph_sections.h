#pragma once
// Sections of the morph panel (morph_panel.h), each in its own file.
#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "ui/widgets/drag_merge.h"
#include "ui/inspector/morph_panel.h"
#include "ui/common/status_bar.h"

namespace animorph {

// Easing and blend preset buttons; noise amplitude (keyed at the current
// morph progress) and frequency. morph_panel.cpp.
void drawMorphCurveSettings(Document& doc, DragMerge& drag, StatusMessage& status);

// The pose used for projection, the projection limits, re-projection, and the
// report of the prepared morph (fallbacks, failures, notes). morph_projection_panel.cpp.
void drawMorphProjection(Document& doc, const MorphPanelState& st, DragMerge& drag);

// The inspector's "Chain matching" section: drawChainMatching (morph_panel.h) under a
// collapsing header, its widgets noted as morph/chains/... morph_chains_panel.cpp.
void drawMorphChains(Document& doc, MorphPanelState& st);

// The stand-in segments of source and target, and the selected one's A / B
// offsets and radius scale at the current morph progress with key buttons.
// morph_segments_panel.cpp.
void drawMorphSegments(Document& doc, AssetCache& assets, MorphPanelState& st, DragMerge& drag, StatusMessage& status);

}  // namespace animorph
