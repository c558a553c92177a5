#include "core/export/frame_chunks.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace animorph {

std::vector<FrameChunk> splitFrames(int first, int last, int chunkFrames) {
  std::vector<FrameChunk> chunks;
  if (first < 0 || last < first || chunkFrames < 1) return chunks;
  for (long long a = first; a <= last; a += chunkFrames)
    chunks.push_back({int(a), int(std::min<long long>(a + chunkFrames - 1, last))});
  return chunks;
}

std::string chunkGltfName(const std::string& dir, const std::string& name, const FrameChunk& chunk) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "_%04d-%04d.glb", chunk.first, chunk.last);
  return (std::filesystem::path(dir) / (name + buf)).string();
}

}  // namespace animorph
