#include "core/poly/scrubbing_grid.h"

namespace animorph {

PolygonizeGrid holdScrubbingGrid(const PolygonizeGrid& own, const std::optional<PolygonizeGrid>& previous,
                                 float coarser) {
  if (own.empty || !previous || previous->empty || previous->cellSize > coarser * own.cellSize) return own;
  for (int a = 0; a < 3; ++a) {
    const float mine0 = own.origin[a], mine1 = own.origin[a] + own.cellSize * float(own.cells[a]);
    const float theirs0 = previous->origin[a], theirs1 = previous->origin[a] + previous->cellSize * float(previous->cells[a]);
    if (mine0 < theirs0 || mine1 > theirs1) return own;
  }
  return *previous;
}

}  // namespace animorph
