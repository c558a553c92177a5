#pragma once
// Writing meshes: Wavefront OBJ, binary PLY and glTF binary (GLB, a minimal
// writer: one mesh, POSITION + NORMAL + indices). Writes are atomic.
// Vertex colours, when the mesh has them (TriangleMesh::colors, linear light): OBJ
// "v x y z r g b" and PLY uchar red/green/blue (times 255) in sRGB, as Blender, MeshLab and
// other viewers read them (math/color.h's linearToSrgb, clamped to [0, 1]); PLY alpha as
// stored (times 255); GLB COLOR_0 (RGBA float, linear, as glTF requires).
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
