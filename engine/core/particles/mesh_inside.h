#pragma once
// The inside of a triangle mesh on lattices, for Convert to particles (docs/particles.md): a
// lattice point is inside where the mesh winds around it (non-zero winding number), counted along
// rays. Every lattice column (a line of points along one axis) gathers the triangles whose
// projection covers it -- each triangle is dropped into the columns its projected box spans, so
// a 50k-triangle mesh costs one pass over the triangles and their crossings per lattice --,
// intersects them (a consistent rule on shared edges and vertices: a ray through an edge counts
// it once), and a point's winding number is the sum of the signs of the crossings past it. Exact
// for a closed mesh, whatever its orientation, and overlapping closed parts give their union.
// A mesh with holes (boundary edges, counted after welding vertices at equal positions) has no
// inside of its own: its points take the majority of the rays along x, y and z, which bridges
// holes smaller than the shape's thickness; the count is reported.
#include <cstddef>
#include <vector>

#include "core/math/bounds.h"
#include "core/particles/convert_to_particles.h"
#include "core/poly/mesh.h"

namespace animorph {

struct MeshInsideInfo {
  size_t triangles = 0;      // non-degenerate triangles used
  size_t boundaryEdges = 0;  // edges with one triangle after welding: 0 for a closed mesh
  double volume = 0.0;       // |signed volume| (divergence theorem), meaningful when closed
  Bounds bounds;
};

class MeshInside {
 public:
  // Copies the mesh's positions and triangles (welded at equal positions).
  explicit MeshInside(const TriangleMesh& mesh);
  const MeshInsideInfo& info() const { return info_; }
  bool closed() const { return info_.boundaryEdges == 0; }
  // inside[lattice.index(i, j, k)]: 1 where the point is inside (see above), in parallel (TBB).
  std::vector<uint8_t> insideOnLattice(const SampleLattice& lattice) const;

 private:
  // Non-zero winding along rays parallel to axis (0, 1, 2) through every lattice column.
  std::vector<uint8_t> windingAlong(int axis, const SampleLattice& lattice) const;
  std::vector<glm::vec3> positions_;
  std::vector<glm::uvec3> triangles_;
  MeshInsideInfo info_;
};

// The mesh's inside as a ParticleShape (the MeshInside must outlive it). Errors: no triangle, a
// flat mesh (its box has no thickness).
Result<ParticleShape> meshParticleShape(const MeshInside& mesh);

}  // namespace animorph
