#pragma once
// The viewport's "Stand-ins" overlay: every posed stand-in segment as a wire
// capsule (scene/standin_guides.h) in the overlay line batch, the selected
// actor's brighter and its selected segment highlighted.
#include <string>
#include <vector>

#include "gpu/render/line_batch.h"
#include "core/scene/standin_guides.h"

namespace animorph::gpu {

// selectedSegment: an index into selectedActorId's stand-in, or -1.
void addStandinOverlay(const std::vector<StandinGuides>& guides, const std::string& selectedActorId,
                       int selectedSegment, LineBatch& overlay);

}  // namespace animorph::gpu
