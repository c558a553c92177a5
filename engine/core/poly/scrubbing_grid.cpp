#include "core/poly/scrubbing_grid.h"

#include <algorithm>
#include <cmath>

namespace animorph {

namespace {

// own on previous's lattice (see holdScrubbingGrid), or own when the cell size or the extent did not hold.
PolygonizeGrid followOnLattice(const PolygonizeGrid& own, const PolygonizeGrid& previous, float coarser,
                               int latticeCells) {
  if (own.cellSize > coarser * previous.cellSize) return own;
  const float h = previous.cellSize, step = h * float(latticeCells);
  PolygonizeGrid g = previous;
  for (int a = 0; a < 3; ++a) {
    const float mine0 = own.origin[a], mine1 = own.origin[a] + own.cellSize * float(own.cells[a]);
    if (mine1 - mine0 > h * (float(previous.cells[a]) + 1e-3f)) return own;  // grew past the grid (not rounding)
    const float k = std::floor((mine0 - previous.origin[a]) / step);
    g.origin[a] = previous.origin[a] + k * step;
    const int cells = int(std::ceil((mine1 - g.origin[a]) / h - 1e-4f));
    if (cells > 2048) return own;
    g.cells[a] = std::max(cells, 1);
  }
  return g;
}

}  // namespace

PolygonizeGrid holdScrubbingGrid(const PolygonizeGrid& own, const std::optional<PolygonizeGrid>& previous,
                                 float coarser, int latticeCells) {
  if (own.empty || !previous || previous->empty || previous->cellSize > coarser * own.cellSize) return own;
  for (int a = 0; a < 3; ++a) {
    const float mine0 = own.origin[a], mine1 = own.origin[a] + own.cellSize * float(own.cells[a]);
    const float theirs0 = previous->origin[a], theirs1 = previous->origin[a] + previous->cellSize * float(previous->cells[a]);
    if (mine0 < theirs0 || mine1 > theirs1)
      return latticeCells > 0 ? followOnLattice(own, *previous, coarser, latticeCells) : own;
  }
  return *previous;
}

}  // namespace animorph
