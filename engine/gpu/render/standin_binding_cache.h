#pragma once
// GPU copies of the stand-in bindings of prepared morphs (one MorphRuntime per
// document revision): uploaded on first use, released some frames after their
// runtime is gone, once the GPU can no longer be using them. The transition
// draws of the editor read them every frame; nothing is uploaded per frame.
#include <map>
#include <memory>
#include <string>

#include "gpu/vulkan/context.h"
#include "gpu/transition/gpu_standin_binding.h"
#include "core/scene/morph_runtime.h"

namespace animorph::gpu {

class StandinBindingCache {
 public:
  explicit StandinBindingCache(Context& ctx) : ctx_(ctx) {}
  // The binding of rt's target (target true) or source, with its weight map,
  // uploading it if needed. Null when the upload failed (lastError(); not retried).
  const GpuStandinBinding* get(const std::shared_ptr<const MorphRuntime>& rt, bool target);
  // Call once per frame: frees bindings of runtimes released more than
  // kFramesInFlight + 1 frames ago.
  void endFrame();
  const std::string& lastError() const { return lastError_; }
  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::weak_ptr<const MorphRuntime> owner;
    std::unique_ptr<GpuStandinBinding> bindings[2];  // [target]
    bool failed[2] = {false, false};
    uint64_t lastUsedFrame = 0;
  };
  Context& ctx_;
  std::map<const MorphRuntime*, Entry> entries_;
  uint64_t frame_ = 0;
  std::string lastError_;
};

}  // namespace animorph::gpu
