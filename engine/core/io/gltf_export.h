#pragma once
// glTF 2.0 binary (.glb) export of a Character.
#include <string>

#include "core/rig/character.h"
#include "core/util/result.h"

namespace animorph {

// Serialises c as GLB bytes: nodes (TRS), meshes (POSITION, NORMAL, COLOR_0 when present,
// TEXCOORD_0, indices, JOINTS_0/WEIGHTS_0 and _1 when used, for meshes drawn with a skin; a mesh
// with two or more material parts (Mesh::parts) as one primitive per part, sharing the vertex
// attributes, each with its indices and material; materials with their base colour factor and
// texture (embedded PNG); morph
// targets with POSITION and NORMAL deltas, their names in extras.targetNames and
// the default weights), skins
// with inverse bind matrices, animations with STEP/LINEAR/CUBICSPLINE
// samplers (translation, rotation, scale, morph target weights), one scene of c.roots. Fails (naming the element) on data glTF
// cannot hold: indices or joints out of range, key times that do not
// increase, a value count that does not match the interpolation.
Result<std::string> exportGlbBytes(const Character& c);

// exportGlbBytes written atomically to path; errors name the file.
Status exportGlb(const Character& c, const std::string& path);

}  // namespace animorph
