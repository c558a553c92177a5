#pragma once
// glTF 2.0 import (.gltf and .glb) into a Character.
#include <cstddef>
#include <string>

#include "core/rig/character.h"
#include "core/util/result.h"

namespace animorph {

// Imports meshes (triangles; indexed or not; normals computed when missing),
// skins, the node hierarchy and animations (translation/rotation/scale with
// STEP, LINEAR, CUBICSPLINE). Weight sums are normalised and counted in the
// report; unsupported features are listed by name in the report. External
// URIs are resolved only inside the file's own directory.
// Errors name the file as given, the element and the reason, e.g.
// "assets/tentacle.glb: accessor 7: index 9000 out of range (4096 vertices)".
//
// Decoding budget: all accessors together are decoded into at most
// kGltfDecodeFactor times the input's size (the file plus the buffers it
// loads) plus kGltfDecodeAllowance bytes; the budget is charged before an
// accessor's array is allocated, so an accessor without a bufferView that
// declares a huge count in a tiny file is refused at once. An accessor used
// by several primitives, skins or animation channels is decoded once.
inline constexpr size_t kGltfDecodeFactor = 8;
inline constexpr size_t kGltfDecodeAllowance = size_t(16) << 20;
Result<Character> importGltf(const std::string& path);

// True when path names a glTF file rather than a project: a .gltf or .glb extension (any case),
// or a file whose first four bytes are the GLB magic "glTF". Reads at most 4 bytes of a regular
// file; false for a file that cannot be opened.
bool isGltfPath(const std::string& path);

}  // namespace animorph
