#include "core/animorphosis/assignment.h"

#include <cstddef>
#include <limits>

namespace animorph {

using std::size_t;

namespace {

// rows <= cols. Rows and columns are 1-based inside; column 0 is the virtual start.
std::vector<int> assignWide(const std::vector<double>& cost, int rows, int cols, bool transposed) {
  auto at = [&](int r, int c) { return transposed ? cost[size_t(c) * size_t(rows) + size_t(r)] : cost[size_t(r) * size_t(cols) + size_t(c)]; };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(size_t(rows) + 1, 0.0), v(size_t(cols) + 1, 0.0);
  std::vector<int> rowOfCol(size_t(cols) + 1, 0), way(size_t(cols) + 1, 0);
  for (int r = 1; r <= rows; ++r) {
    rowOfCol[0] = r;
    int c0 = 0;
    std::vector<double> minv(size_t(cols) + 1, inf);
    std::vector<char> used(size_t(cols) + 1, 0);
    do {
      used[size_t(c0)] = 1;
      int r0 = rowOfCol[size_t(c0)], c1 = 0;
      double delta = inf;
      for (int c = 1; c <= cols; ++c) {
        if (used[size_t(c)]) continue;
        double cur = at(r0 - 1, c - 1) - u[size_t(r0)] - v[size_t(c)];
        if (cur < minv[size_t(c)]) {
          minv[size_t(c)] = cur;
          way[size_t(c)] = c0;
        }
        if (minv[size_t(c)] < delta) {
          delta = minv[size_t(c)];
          c1 = c;
        }
      }
      for (int c = 0; c <= cols; ++c) {
        if (used[size_t(c)]) {
          u[size_t(rowOfCol[size_t(c)])] += delta;
          v[size_t(c)] -= delta;
        } else {
          minv[size_t(c)] -= delta;
        }
      }
      c0 = c1;
    } while (rowOfCol[size_t(c0)] != 0);
    do {
      int c1 = way[size_t(c0)];
      rowOfCol[size_t(c0)] = rowOfCol[size_t(c1)];
      c0 = c1;
    } while (c0 != 0);
  }
  std::vector<int> colOfRow(size_t(rows), -1);
  for (int c = 1; c <= cols; ++c)
    if (rowOfCol[size_t(c)] > 0) colOfRow[size_t(rowOfCol[size_t(c)] - 1)] = c - 1;
  return colOfRow;
}

}  // namespace

std::vector<int> minCostAssignment(const std::vector<double>& cost, int rows, int cols) {
  if (rows == 0 || cols == 0) return std::vector<int>(size_t(rows), -1);
  if (rows <= cols) return assignWide(cost, rows, cols, false);
  // More rows than columns: assign each column a row, then invert.
  std::vector<int> rowOfCol = assignWide(cost, cols, rows, true);
  std::vector<int> colOfRow(size_t(rows), -1);
  for (int c = 0; c < cols; ++c)
    if (rowOfCol[size_t(c)] >= 0) colOfRow[size_t(rowOfCol[size_t(c)])] = c;
  return colOfRow;
}

}  // namespace animorph
