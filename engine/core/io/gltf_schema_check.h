#pragma once
// Type checks on the glTF JSON that tinygltf does not make (it silently
// ignores a property of the wrong type, e.g. "scene": "hello").
#include <string>
#include <vector>

#include "core/util/result.h"

namespace animorph {

// Checks the JSON of a .gltf (or the JSON chunk of a .glb, given whole) for
// properties of the wrong type. Properties that decide geometry, hierarchy,
// skins or animation give an error ("file: meshes[0].primitives: expected an
// array, found object"); wrongly typed material, texture and naming
// properties are appended to warnings (the importer ignores them anyway).
//
// Animation channels that animate no node (KHR_animation_pointer targets, e.g. KHR_node_visibility
// as our own sequence exporter writes them) are valid glTF that tinygltf refuses: they are ignored
// with a warning, and *withoutPointerChannels receives the file without them (the same container:
// .gltf text, or a GLB with its BIN chunk unchanged). It stays empty when the file has none.
Status checkGltfSchema(const std::string& fileBytes, const std::string& fileName, std::vector<std::string>& warnings,
                       std::string* withoutPointerChannels = nullptr);

}  // namespace animorph
