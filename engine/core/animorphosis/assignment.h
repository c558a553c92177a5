#pragma once
// Minimum-cost assignment between the rows and columns of a cost matrix
// (rectangular allowed): the Hungarian method with potentials, O(n^2 m).
#include <vector>

namespace animorph {

// cost[r * cols + c], finite. Returns, per row, its column or -1 (when rows > cols,
// rows - cols rows stay unassigned). The sum of the chosen costs is minimal.
std::vector<int> minCostAssignment(const std::vector<double>& cost, int rows, int cols);

}  // namespace animorph
