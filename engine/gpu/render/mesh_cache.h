#pragma once
// GPU copies of the meshes of loaded characters, uploaded on first use and
// released some frames after their character is gone (reloaded or removed),
// once the GPU can no longer be using them.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpu/vulkan/context.h"
#include "gpu/render/gpu_mesh.h"
#include "core/rig/character.h"

namespace animorph::gpu {

class MeshCache {
 public:
  explicit MeshCache(Context& ctx) : ctx_(ctx) {}
  // The GPU mesh for character->meshes[meshIndex], uploading it if needed.
  // Null when the upload failed (lastError() says why; not retried).
  const GpuMesh* get(const std::shared_ptr<const Character>& character, int meshIndex);
  // Call once per frame: frees meshes of characters released more than
  // kFramesInFlight + 1 frames ago.
  void endFrame();
  const std::string& lastError() const { return lastError_; }
  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::weak_ptr<const Character> owner;
    std::vector<std::unique_ptr<GpuMesh>> meshes;  // by mesh index
    std::vector<char> failed;
    uint64_t lastUsedFrame = 0;
  };
  Context& ctx_;
  std::map<const Character*, Entry> entries_;
  uint64_t frame_ = 0;
  std::string lastError_;
};

}  // namespace animorph::gpu
