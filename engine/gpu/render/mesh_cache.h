#pragma once
// GPU copies of the meshes of loaded characters, uploaded on first use and
// released some frames after their character is gone (reloaded or removed),
// once the GPU can no longer be using them. A character's textures are uploaded
// with its first mesh, once per pixel buffer and sampler (copies of a character,
// which share their TextureImage pixels, share the GPU texture), and given to
// each mesh's material parts.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpu/vulkan/context.h"
#include "gpu/render/gpu_mesh.h"
#include "gpu/render/gpu_texture.h"
#include "core/rig/character.h"

namespace animorph::gpu {

class MeshCache {
 public:
  explicit MeshCache(Context& ctx) : ctx_(ctx) {}
  // The GPU mesh for character->meshes[meshIndex], uploading it (and the character's
  // textures) if needed. Null when the upload failed (lastError() says why; not retried).
  // A texture that fails to upload leaves its parts in their factor colour (lastError()).
  const GpuMesh* get(const std::shared_ptr<const Character>& character, int meshIndex);
  // Call once per frame: frees meshes of characters released more than
  // kFramesInFlight + 1 frames ago.
  void endFrame();
  const std::string& lastError() const { return lastError_; }
  size_t size() const { return entries_.size(); }
  size_t textureCount() const { return textures_.size(); }

 private:
  struct Entry {
    std::weak_ptr<const Character> owner;
    std::vector<std::unique_ptr<GpuMesh>> meshes;  // by mesh index
    std::vector<char> failed;
    std::vector<VkDescriptorSet> textureSets;  // by texture index; null: not uploaded
    bool texturesResolved = false;
    uint64_t lastUsedFrame = 0;
  };
  // One uploaded texture: its pixel buffer (weak: released with the last character using it).
  struct TextureEntry {
    std::weak_ptr<const std::vector<uint8_t>> pixels;
    std::unique_ptr<GpuTexture> texture;
    uint64_t lastUsedFrame = 0;  // the last frame its pixels were alive
  };
  using TextureKey = std::pair<const std::vector<uint8_t>*, int>;  // pixels, sampler code
  void resolveTextures(const Character& character, Entry& e);
  Context& ctx_;
  std::map<const Character*, Entry> entries_;
  std::map<TextureKey, TextureEntry> textures_;
  uint64_t frame_ = 0;
  std::string lastError_;
};

}  // namespace animorph::gpu
