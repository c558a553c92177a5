#pragma once
// Distances from points to a triangle mesh (exact point-triangle distances,
// triangles bucketed in a uniform grid), used to measure seams between the
// transition meshes and the polygonised morph.
#include <vector>

#include <glm/glm.hpp>

#include "core/poly/mesh.h"

namespace animorph {

struct PointMeshDistances {
  double maxDistance = 0.0;
  double meanDistance = 0.0;
  size_t points = 0;
};

// Unsigned distance of each point to the closest triangle of mesh. An empty
// mesh gives infinite distances.
PointMeshDistances pointsToMeshDistance(const std::vector<glm::vec3>& points, const TriangleMesh& mesh);

// The same, one distance per point (infinite ones for an empty mesh).
std::vector<float> pointDistancesToMesh(const std::vector<glm::vec3>& points, const TriangleMesh& mesh);

// The largest of those distances alone (0 without points; infinite for an empty mesh), exactly as
// pointsToMeshDistance's maxDistance, but a point closer than the largest distance found so far
// stops at the first triangle that close: for two nearby meshes (consecutive frames) a few
// triangles per point instead of every triangle around it.
double maxPointToMeshDistance(const std::vector<glm::vec3>& points, const TriangleMesh& mesh);

}  // namespace animorph
