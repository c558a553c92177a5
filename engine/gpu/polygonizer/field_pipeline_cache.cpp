#include "gpu/polygonizer/field_pipeline_cache.h"

#include <algorithm>
#include <chrono>

namespace animorph::gpu {

Result<FieldPipelines> FieldPipelineCache::get(const FieldVariantKey& key) {
  if (auto it = variants_.find(key); it != variants_.end()) return it->second;
  Result<FieldPipelines> made = Error{""};
  if (auto it = compiling_.find(key); it != compiling_.end()) {  // prewarmed: wait for it
    made = it->second.get();
    compiling_.erase(it);
  } else {
    made = create_(key);
  }
  if (made) variants_.emplace(key, *made);
  return made;
}

void FieldPipelineCache::prewarm(const FieldVariantKey& key) {
  if (variants_.count(key) || compiling_.count(key)) return;
  Create create = create_;
  compiling_.emplace(key, std::async(std::launch::async, [create, key] { return create(key); }));
}

bool FieldPipelineCache::ready(const FieldVariantKey& key) const {
  if (variants_.count(key)) return true;
  auto it = compiling_.find(key);
  return it != compiling_.end() && it->second.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

bool FieldPipelineCache::waitForCompilation(double timeoutSec) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(std::max(0.0, timeoutSec));
  for (const auto& [key, f] : compiling_)
    if (f.wait_until(deadline) != std::future_status::ready) return false;
  return true;
}

void FieldPipelineCache::finishCompiling() {
  for (auto& [key, f] : compiling_)
    if (Result<FieldPipelines> r = f.get(); r) variants_.emplace(key, *r);
  compiling_.clear();
}

void FieldPipelineCache::destroy(VkDevice dev) {
  finishCompiling();
  for (auto& [key, v] : variants_)
    for (VkPipeline p : {v.blocks, v.cells, v.emit, v.normals})
      if (p) vkDestroyPipeline(dev, p, nullptr);
  variants_.clear();
}

}  // namespace animorph::gpu
