#pragma once
// What a click in the viewport selects: the editor's rule, kept out of the frame loop so it can be
// tested. A skeleton marker under the cursor selects its node (markers sit on top of surfaces); else
// the nearest surface hit selects its actor; a click on nothing clears the selection, unless the
// click extends it (Shift), which keeps it.
#include <optional>

#include "core/doc/document.h"
#include "editor/blob_pick.h"
#include "editor/pick.h"

namespace animorph {

// The nearer of two hits along the same ray (either may be absent).
std::optional<ScenePick> nearerPick(std::optional<ScenePick> a, std::optional<ScenePick> b);

// The selection after a click: guide (a skeleton marker near the cursor), hit (the nearest surface
// along the click's ray), extend (Shift held).
Selection selectionAfterClick(const Selection& current, const std::optional<BlobGuidePick>& guide,
                              const std::optional<ScenePick>& hit, bool extend);

}  // namespace animorph
