#pragma once
// The grid a scrubbed preview holds from one frame to the next (the CPU worker's scrubbingGrid in
// poly/polygonizer.h, the GPU preview's PreviewFieldCompiler): blocks can only be reused between
// frames polygonised on the same grid.
#include <optional>

#include "core/poly/polygonizer.h"

namespace animorph {

// previous when the grid `own` this frame would get alone lies inside it and previous's cells are at
// most `coarser` times own's; otherwise own (also when own is empty or there is no previous grid).
PolygonizeGrid holdScrubbingGrid(const PolygonizeGrid& own, const std::optional<PolygonizeGrid>& previous,
                                 float coarser = 1.25f);

}  // namespace animorph
