#pragma once
// Writing meshes: Wavefront OBJ, binary PLY and glTF binary (GLB, a minimal
// writer: one mesh, POSITION + NORMAL + indices). Writes are atomic.
// Vertex colours, when the mesh has them: OBJ "v x y z r g b" (the values as
// stored), PLY uchar red/green/blue/alpha (clamped to [0, 1], times 255),
// GLB COLOR_0 (RGBA float).
#include <string>

#include "core/poly/mesh.h"
#include "core/util/result.h"

namespace animorph {

Status writeObj(const TriangleMesh& mesh, const std::string& path);
Status writePly(const TriangleMesh& mesh, const std::string& path);
Status writeGlb(const TriangleMesh& mesh, const std::string& path);

// Writes by the file's extension (.obj, .ply, .glb); other extensions are an error naming the file.
Status writeMesh(const TriangleMesh& mesh, const std::string& path);

// The bytes of the GLB (for tests and in-memory use).
std::string glbBytes(const TriangleMesh& mesh);

}  // namespace animorph
