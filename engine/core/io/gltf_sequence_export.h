#pragma once
// Animated glTF 2.0 (.glb) of a mesh sequence whose topology may change every
// frame (the baked morph): one mesh per frame, each shown only on its frame.
//
// Contract of the written file:
// * Frame i of the sequence is scene frame firstFrame + i. Its node is named
//   "NAME_####" (the scene frame, 4-digit padded) and is a child of one root
//   node "NAME"; a frame whose mesh has no triangles has a node without mesh.
// * Visibility in core glTF: one animation "NAME" with a STEP scale channel per
//   frame node: scale 1 from the key time frame/fps until the next frame's key
//   time, 0 elsewhere (keys 0 -> 1 -> 0). The first frame's node stays shown
//   before the range, the last one's after it. At rest (no animation played)
//   only the first frame's node has scale 1.
// * Optionally (options.nodeVisibility) the same as KHR_node_visibility
//   "visible" flags animated through KHR_animation_pointer with the same STEP
//   keys, both listed in extensionsUsed only (importers that do not know them
//   ignore them and still get the scale keys).
// * Meshes: POSITION (with min/max), NORMAL (unit) when the frame has normals,
//   COLOR_0 (RGBA float) when it has colours, indices (unsigned short when the
//   frame has at most 65535 vertices). Frames whose meshes are identical (same
//   bytes in every attribute and the indices) share one glTF mesh.
// * scenes[0].extras holds {"fps", "frameStart", "frameEnd"}.
#include <memory>
#include <string>

#include "core/poly/mesh.h"
#include "core/util/result.h"

namespace animorph {

struct GltfSequenceOptions {
  std::string name = "sequence";  // the root node, the animation and the frame nodes' prefix
  double fps = 24.0;              // key time of scene frame f: f / fps
  int firstFrame = 0;             // the scene frame of the first added mesh (>= 0)
  bool nodeVisibility = true;     // add KHR_node_visibility + KHR_animation_pointer
};

class GltfSequenceWriter {
 public:
  explicit GltfSequenceWriter(GltfSequenceOptions options);
  ~GltfSequenceWriter();
  GltfSequenceWriter(const GltfSequenceWriter&) = delete;
  GltfSequenceWriter& operator=(const GltfSequenceWriter&) = delete;

  // Appends the next frame (scene frame firstFrame + frameCount()). Its data is
  // copied into the binary buffer at once, so the caller may drop the mesh.
  // Fails, naming the frame, on data glTF cannot hold (an index out of range,
  // normals or colours that do not match the vertex count); nothing is added then.
  Status addFrame(const TriangleMesh& mesh);

  int frameCount() const;
  int meshCount() const;  // distinct meshes stored so far (frameCount() minus repeats and empty frames)

  // The .glb bytes of the frames added so far; fails when there is none, or
  // when options are invalid (fps <= 0, firstFrame < 0). Call once.
  Result<std::string> finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// finish() written atomically to path (a temporary beside it, then a rename:
// no half-written file on failure); errors name the file.
Status writeGltfSequence(GltfSequenceWriter& writer, const std::string& path);

}  // namespace animorph
