#pragma once
// glTF 2.0 import (.gltf and .glb) into a Character.
#include <string>

#include "rig/character.h"
#include "util/result.h"

namespace animorph {

// Imports meshes (triangles; indexed or not; normals computed when missing),
// skins, the node hierarchy and animations (translation/rotation/scale with
// STEP, LINEAR, CUBICSPLINE). Weight sums are normalised and counted in the
// report; unsupported features are listed by name in the report. External
// URIs are resolved only inside the file's own directory.
// Errors name the file, the element and the reason, e.g.
// "tentacle.glb: accessor 7: index 9000 out of range (4096 vertices)".
Result<Character> importGltf(const std::string& path);

// True when path names a glTF file rather than a project: a .gltf or .glb extension (any case),
// or a file whose first four bytes are the GLB magic "glTF". Reads at most 4 bytes of a regular
// file; false for a file that cannot be opened.
bool isGltfPath(const std::string& path);

}  // namespace animorph
