#pragma once
// Packing per-vertex skin influences into the Mesh layout (two sets of four).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace animorph {

// One (joint, weight) pair of a vertex.
struct Influence {
  uint32_t joint = 0;
  float weight = 0.0f;
};

// What packing changed, summed over vertices.
struct InfluenceStats {
  size_t normalised = 0;  // weight sum off 1 by more than kWeightSumTolerance
  size_t dropped = 0;     // more than Mesh::kMaxInfluences non-zero weights
  size_t unweighted = 0;  // no positive weight at all: bound to joint 0 with weight 1
};

// Sums within this distance of 1 count as already normalised (float noise of
// exporters); all sums are still rescaled to exactly 1.
inline constexpr float kWeightSumTolerance = 1e-3f;

// Merges duplicate joints, discards non-positive and non-finite weights, keeps the
// 8 largest, normalises them to sum 1 and writes them sorted by decreasing
// weight into (j0, w0, j1, w1); unused slots get joint 0 weight 0. Updates stats.
void packInfluences(std::vector<Influence>& influences, glm::uvec4& j0, glm::vec4& w0, glm::uvec4& j1,
                    glm::vec4& w1, InfluenceStats& stats);

}  // namespace animorph
