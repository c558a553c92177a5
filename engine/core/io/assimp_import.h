#pragma once
// FBX (binary and ASCII), Collada (.dae) and OBJ import through assimp into a Character,
// beside io/gltf_import.h for glTF. Only io/assimp_import.cpp includes assimp's headers.
#include <cstddef>
#include <string>

#include "core/rig/character.h"
#include "core/util/result.h"

namespace animorph {

// Caps on what one file may hold; a file over any of them is refused with the count.
struct AssimpImportLimits {
  size_t maxFileBytes = size_t(512) << 20;  // the file itself (and each file it references)
  size_t maxVertices = 20'000'000;          // all meshes together
  size_t maxTriangles = 40'000'000;
  size_t maxNodes = 1'000'000;
  size_t maxBonesPerMesh = 65'535;
  size_t maxAnimationKeys = 50'000'000;  // all channels of all clips together
  size_t maxBlendShapeVertices = 20'000'000;  // blend shapes x their mesh's vertices, all meshes
};

// Imports meshes (triangulated; points and lines dropped and listed; normals computed when
// missing), skins (any number of influences per vertex, normalised, the 8 strongest kept and
// the drops counted, as glTF does), the node hierarchy, every animation clip (node
// translation / rotation / scale keys, linear), materials' base colour and base colour
// texture, blend shapes (FBX blend shape channels with their DeformPercent values, read beside
// assimp by io/fbx_shape_values, and their weight animation as Weights channels; Collada morph
// controllers, read beside assimp by io/collada_morphs, with their weights; deltas from the base
// mesh), and
// the file's length unit (FBX UnitScaleFactor, Collada <unit meter>; OBJ has
// none: metres assumed). Geometry stays in the file's units, turned to +Y up (FBX axis
// settings, Collada up_axis). FBX pivots and pre-rotations (assimp's "$AssimpFbx$" helper
// nodes) are kept as nodes where they are animated and folded into one node where not.
// Before assimp parses anything, the file must be a regular file under maxFileBytes whose
// declared arrays fit the decoding budget (io/declared_size_check.h); the files it refers to
// (OBJ .mtl, textures) must lie inside its folder. Errors name the path as given, the element
// and the reason, e.g. "rigs/hero.fbx: mesh 2 'Body': bone 'hand_L' names no node".
Result<Character> importAssimp(const std::string& path, const AssimpImportLimits& limits = {});

}  // namespace animorph
