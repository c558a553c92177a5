#pragma once
// The grid a scrubbed preview holds from one frame to the next (the CPU worker's scrubbingGrid in
// poly/polygonizer.h, the GPU preview's PreviewFieldCompiler): blocks can only be reused between
// frames polygonised on the same grid.
#include <optional>

#include "core/poly/polygonizer.h"

namespace animorph {

// previous when the grid `own` this frame would get alone lies inside it and previous's cells are at
// most `coarser` times own's; otherwise own (also when own is empty or there is no previous grid).
// With latticeCells > 0, a shape that moved out of previous keeps previous's lattice while the cell
// size holds (each within `coarser` times the other) and own is no larger than previous on any
// axis: previous's cell size, its origin moved by whole steps of latticeCells cells to the step at
// or below own's, its cells just covering own. The blocks both frames share are then the same world
// blocks (the CPU polygoniser's history remaps them: scrubbingGrid passes its superblock's cells).
PolygonizeGrid holdScrubbingGrid(const PolygonizeGrid& own, const std::optional<PolygonizeGrid>& previous,
                                 float coarser = 1.25f, int latticeCells = 0);

}  // namespace animorph
