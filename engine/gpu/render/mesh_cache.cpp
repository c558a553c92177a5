#include "gpu/render/mesh_cache.h"

#include "shared_constants.h"

namespace animorph::gpu {

const GpuMesh* MeshCache::get(const std::shared_ptr<const Character>& character, int meshIndex) {
  if (!character || meshIndex < 0 || meshIndex >= static_cast<int>(character->meshes.size())) return nullptr;
  Entry& e = entries_[character.get()];
  if (e.owner.expired() && !e.meshes.empty()) {
    // The address was reused by a new character: drop the stale uploads.
    ctx_.waitIdle();
    e = Entry{};
  }
  e.owner = character;
  e.lastUsedFrame = frame_;
  if (e.meshes.size() != character->meshes.size()) {
    e.meshes.resize(character->meshes.size());
    e.failed.assign(character->meshes.size(), 0);
  }
  auto& slot = e.meshes[static_cast<size_t>(meshIndex)];
  if (!slot && !e.failed[static_cast<size_t>(meshIndex)]) {
    auto up = GpuMesh::upload(ctx_, character->meshes[static_cast<size_t>(meshIndex)]);
    if (up) {
      resolveTextures(*character, e);
      (*up)->setMaterials(character->materials, e.textureSets);
      slot = std::move(*up);
    } else {
      e.failed[static_cast<size_t>(meshIndex)] = 1;
      lastError_ = up.error();
    }
  }
  return slot.get();
}

void MeshCache::resolveTextures(const Character& character, Entry& e) {
  if (e.texturesResolved) return;
  e.texturesResolved = true;
  e.textureSets.assign(character.textures.size(), VK_NULL_HANDLE);
  for (size_t i = 0; i < character.textures.size(); ++i) {
    const TextureImage& t = character.textures[i];
    if (!t.valid()) continue;
    const int sampler = int(t.wrapS) | int(t.wrapT) << 2 | int(t.magFilter) << 4 | int(t.minFilter) << 5;
    TextureEntry& te = textures_[{t.rgba.get(), sampler}];
    if (te.pixels.expired() && te.texture) {  // the address was reused by new pixels
      ctx_.waitIdle();
      te = TextureEntry{};
    }
    te.pixels = t.rgba;
    te.lastUsedFrame = frame_;
    if (!te.texture) {
      auto up = GpuTexture::upload(ctx_, t);
      if (!up) {
        lastError_ = up.error();
        continue;
      }
      te.texture = std::move(*up);
    }
    e.textureSets[i] = te.texture->set();
  }
}

void MeshCache::endFrame() {
  ++frame_;
  for (auto it = entries_.begin(); it != entries_.end();) {
    bool stale = it->second.owner.expired() && frame_ - it->second.lastUsedFrame > kFramesInFlight + 1;
    it = stale ? entries_.erase(it) : std::next(it);
  }
  for (auto it = textures_.begin(); it != textures_.end();) {
    // Expired pixels: no character can draw the texture any more; frames recorded before may.
    TextureEntry& te = it->second;
    if (!te.pixels.expired()) te.lastUsedFrame = frame_;
    const bool stale = te.pixels.expired() && frame_ - te.lastUsedFrame > kFramesInFlight + 1;
    it = stale ? textures_.erase(it) : std::next(it);
  }
}

}  // namespace animorph::gpu
