#pragma once
// What a viewer sees of a morph frame (docs/morph.md, "Continuity"). During the
// collapse and the expansion a frame is two closed shells (scene/standin_core.h):
// the transitioned mesh and the stand-in core inside it. The visible surface is
// the boundary of their union: the mesh cut where it enters the core (the core's
// field, exact) and the core cut where it enters the mesh (the signed distance to
// the mesh at its vertices: the distance to the closest triangle, negative inside,
// poly/inside_mesh.h). Frames with one shell are their own visible surface.
// Exports write it (unless told to keep both shells), and the continuity ratio
// (scene/morph_smoothness.h) measures it, so that the hidden core neither counts
// as a jump nor hides a jump of what is seen.
#include <cstddef>

#include "core/scene/morph_runtime.h"
#include "core/poly/mesh.h"

namespace animorph {

struct VisibleSurfaceStats {
  size_t meshTrianglesHidden = 0;  // mesh triangles wholly inside the core, dropped
  size_t coreTrianglesHidden = 0;  // core triangles wholly inside the mesh, dropped
  size_t coreVertices = 0;         // the core's vertices (0: the frame has no core)
  // The largest signed distance of a core vertex to the mesh, m (> 0: outside
  // it, where the core shows); -infinity when there is no core.
  double coreOutside = 0.0;
};

// The visible surface of fr (a frame of rt: evaluateMorphFrame's output, its
// core the last fr.coreTriangles triangles of fr.mesh). Without a core, fr.mesh
// itself. stats (may be null) says what was hidden.
TriangleMesh visibleSurface(const MorphRuntime& rt, const MorphFrame& fr, VisibleSurfaceStats* stats = nullptr);

// fr's mesh split into the transitioned mesh and the core (the last
// fr.coreTriangles triangles, their vertices renumbered from 0).
void splitStandinCore(const MorphFrame& fr, TriangleMesh& mesh, TriangleMesh& core);

}  // namespace animorph
