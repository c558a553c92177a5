#pragma once
// The test characters (tests/tools/make_test_characters.py: Blender's glTF, FBX and Collada exports
// of automatically weighted rigs) as their manifest lists them, shared by the tests that compare
// or fit them.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace animorph::test {

// The entries of DIR/manifest.json ("file", "format", "character", "variant", "unit", ...) whose
// "format" is format ("glb", "fbx", "dae"; every entry when empty), in the manifest's order.
// Empty when DIR has no readable manifest (the fixture needs Blender): the caller skips.
std::vector<nlohmann::json> testCharacterEntries(const std::string& dir, const std::string& format = "");

}  // namespace animorph::test
