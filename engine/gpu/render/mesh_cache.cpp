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
      slot = std::move(*up);
    } else {
      e.failed[static_cast<size_t>(meshIndex)] = 1;
      lastError_ = up.error();
    }
  }
  return slot.get();
}

void MeshCache::endFrame() {
  ++frame_;
  for (auto it = entries_.begin(); it != entries_.end();) {
    bool stale = it->second.owner.expired() && frame_ - it->second.lastUsedFrame > kFramesInFlight + 1;
    it = stale ? entries_.erase(it) : std::next(it);
  }
}

}  // namespace animorph::gpu
