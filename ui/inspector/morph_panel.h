#pragma once
// The morph's settings in the inspector (shown when no actor is selected in a
// project with a morph): the stage markers A..D, the implicit method and its
// parameters, the weight-map shift, easing and blend presets, solid noise, the
// source and target clips' timing, the projection settings and report, and
// the keyed stand-in segment tracks (user-controlled morphing; see
// morph_sections.h). Every edit is a command; a drag is one step.
#include <memory>

#include <glm/glm.hpp>

#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "ui/widgets/drag_merge.h"
#include "core/scene/morph_runtime.h"
#include "core/scene/blob_guides.h"
#include "ui/common/status_bar.h"

namespace animorph {

struct MorphPanelState {
  int segmentSlot = 0;  // whose stand-in segment is selected: 0 source, 1 target
  int segment = -1;     // the selected segment, -1: none
  // The prepared morph the viewport shows (the app sets it; null: none yet).
  // Its projection statistics and notes are the projection report.
  std::shared_ptr<const MorphRuntime> runtime;
  // The chain whose row the pointer is over in Chain matching (-1: none), of
  // the target's rig when hoveredChainTarget; the viewport highlights it.
  int hoveredChain = -1;
  bool hoveredChainTarget = false;
};

// The chain hovered in Chain matching drawn as guides: its stand-in segments
// posed at timeSec (world space) as lines, their ends as markers. Empty when no
// chain is hovered or the prepared morph has no skeleton correspondence.
BlobGuides hoveredChainGuides(const MorphPanelState& st, double timeSec);

// Skeleton correspondence: the source's and the target's chains with their
// pairing, from the prepared morph (st.runtime); per source chain a combo pairs it
// by hand (or leaves it unmatched, or gives it back to the automatic matching),
// each change one command on the morph's chain pairs. Sets st.hoveredChain to the
// row under the pointer (the caller clears it once a frame). Widgets are noted as
// keys + "/source/I", "/option/K", "/reset/I", "/reset-all", "/target/I". Drawn
// by the inspector's Chain matching section and the Correspondence Editor.
void drawChainMatching(Document& doc, MorphPanelState& st, const std::string& keys);

// Refused edits report to status.
void drawMorphSettings(Document& doc, AssetCache& assets, MorphPanelState& st, DragMerge& drag,
                       StatusMessage& status);

}  // namespace animorph
