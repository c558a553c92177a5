#pragma once
// A frame range split into chunks for a render farm: each chunk is baked by its own task (baking
// is per frame and deterministic, so the chunks' frames are the frames of one bake of the whole
// range), and an assembly step joins the chunks' animated glTFs into one.
#include <string>
#include <vector>

namespace animorph {

struct FrameChunk {
  int first = 0, last = 0;  // inclusive scene frames
};

// first..last in consecutive chunks of chunkFrames frames (the last one may be shorter), in order.
// Needs 0 <= first <= last and chunkFrames >= 1 (an empty list otherwise).
std::vector<FrameChunk> splitFrames(int first, int last, int chunkFrames);

// DIR/NAME_AAAA-BBBB.glb: where the task of a chunk writes its animated glTF, which the
// assembly step reads back (frame numbers padded to 4 digits, as frameFileName pads them).
std::string chunkGltfName(const std::string& dir, const std::string& name, const FrameChunk& chunk);

}  // namespace animorph
