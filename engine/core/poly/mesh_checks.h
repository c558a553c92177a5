#pragma once
// Geometric and topological checks of triangle meshes: watertight, manifold,
// orientation, Euler characteristic, connected components, volume, area.
#include <cstddef>

#include "core/poly/mesh.h"

namespace animorph {

struct MeshTopology {
  size_t vertices = 0;             // vertices used by at least one triangle
  size_t edges = 0;                // undirected edges
  size_t faces = 0;
  long long euler = 0;             // V - E + F
  size_t boundaryEdges = 0;        // edges with one triangle
  size_t nonManifoldEdges = 0;     // edges with more than two triangles
  size_t misorientedEdges = 0;     // edges whose two triangles run the same way along them
  size_t nonManifoldVertices = 0;  // vertices whose triangles do not form one closed fan
  size_t degenerateTriangles = 0;  // repeated index, index out of range, or zero area
  size_t components = 0;           // connected components (through shared edges)

  bool watertight() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
  bool manifold() const { return watertight() && nonManifoldVertices == 0 && misorientedEdges == 0; }
  // Genus of a closed orientable surface with this many components: (2C - euler) / 2.
  long long genus() const { return (2 * (long long)components - euler) / 2; }
};

// Analyses the mesh's connectivity (indices only; positions for areas).
MeshTopology analyzeMesh(const TriangleMesh& mesh);

// Signed volume enclosed (divergence theorem); positive when normals point outwards.
double meshVolume(const TriangleMesh& mesh);

}  // namespace animorph
