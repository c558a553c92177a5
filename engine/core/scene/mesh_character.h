#pragma once
// A triangle mesh (polygonised surface, transition output) wrapped as a
// one-node, unskinned Character, so the scene and the renderer draw it like
// any imported character; its vertex colours (when every vertex has one) are
// the mesh's COLOR_0, so a coloured surface is drawn in them.
#include <memory>
#include <string>

#include "core/poly/mesh.h"
#include "core/rig/character.h"

namespace animorph {

std::shared_ptr<const Character> characterFromMesh(const TriangleMesh& mesh, const std::string& name);

}  // namespace animorph
