#pragma once
// A small skinned, animated test character, written as a real .gltf file
// (so a real AssetCache can import it) and registered in memory for the
// tests' own AssetCache while the real one is not linked.
#include <memory>
#include <string>

#include "core/rig/character.h"

namespace animorph::test {

// Writes the character to path (.gltf with an embedded buffer) and returns
// the same character in memory. Nodes: 0 "Body" (skinned mesh), 1 "Armature",
// 2 "hip", 3 "spine". One clip "wave" (1 s) with keys at 0, 0.25, 0.5, 1.0 s
// on spine's rotation and 0, 1.0 s on hip's translation.
Character writeTestCharacter(const std::string& path);

}  // namespace animorph::test
