#pragma once
// Writing meshes: Wavefront OBJ, binary PLY and glTF binary (GLB, a minimal
// writer: one mesh, POSITION + NORMAL + indices). Writes are atomic.
#include <string>

#include "poly/mesh.h"
#include "util/result.h"

namespace animorph {

Status writeObj(const TriangleMesh& mesh, const std::string& path);
Status writePly(const TriangleMesh& mesh, const std::string& path);
Status writeGlb(const TriangleMesh& mesh, const std::string& path);

// Writes by the file's extension (.obj, .ply, .glb); other extensions are an error naming the file.
Status writeMesh(const TriangleMesh& mesh, const std::string& path);

// The bytes of the GLB (for tests and in-memory use).
std::string glbBytes(const TriangleMesh& mesh);

}  // namespace animorph
