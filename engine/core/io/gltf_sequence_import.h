#pragma once
// Reading back the frames of an animated glTF written by GltfSequenceWriter
// (io/gltf_sequence_export.h): how a render farm's assembly step joins the glTFs its chunk tasks
// wrote into one (animorph-cli farm assemble).
#include <string>
#include <vector>

#include "core/poly/mesh.h"
#include "core/util/result.h"

namespace animorph {

struct SequenceFrame {
  int frame = 0;      // the scene frame, from the node's name
  TriangleMesh mesh;  // empty for a frame node without mesh (an empty frame)
};

// Every node of the file named NAME_<digits> (the sequence's frame nodes), in increasing frame
// order, with its mesh. Read through importGltf: positions, indices and colours in [0, 1] come
// back exactly as written, normals re-normalised (within a few ulps of the written unit normals).
// Errors name the file and the reason: unreadable or not glTF, no node named NAME_####, a frame
// named twice.
Result<std::vector<SequenceFrame>> readGltfSequence(const std::string& path, const std::string& name);

}  // namespace animorph
