#include "gpu/render/standin_binding_cache.h"

#include "shared_constants.h"

namespace animorph::gpu {

const GpuStandinBinding* StandinBindingCache::get(const std::shared_ptr<const MorphRuntime>& rt, bool target) {
  if (!rt) return nullptr;
  Entry& e = entries_[rt.get()];
  if (e.owner.expired() && (e.bindings[0] || e.bindings[1] || e.failed[0] || e.failed[1])) {
    // The address was reused by a new runtime: drop the stale uploads.
    ctx_.waitIdle();
    e = Entry{};
  }
  e.owner = rt;
  e.lastUsedFrame = frame_;
  const int k = target ? 1 : 0;
  if (!e.bindings[k] && !e.failed[k]) {
    const MorphActorRuntime& a = target ? rt->target : rt->source;
    auto up = GpuStandinBinding::upload(ctx_, a.binding, a.morph.weightMap);
    if (up) {
      e.bindings[k] = std::move(*up);
    } else {
      e.failed[k] = true;
      lastError_ = "actor '" + a.actor.id + "': " + up.error();
    }
  }
  return e.bindings[k].get();
}

void StandinBindingCache::endFrame() {
  ++frame_;
  for (auto it = entries_.begin(); it != entries_.end();) {
    bool stale = it->second.owner.expired() && frame_ - it->second.lastUsedFrame > kFramesInFlight + 1;
    it = stale ? entries_.erase(it) : std::next(it);
  }
}

}  // namespace animorph::gpu
