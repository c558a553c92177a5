#pragma once
// The GPU polygoniser's field pipelines, one set per variant: the specialisation constants of
// the field's features and primitive kinds, and whether its pool is a storage buffer
// (docs/gpu-polygonizer.md, "Specialisation"). A variant is compiled on first use, or ahead of
// it on a background thread (prewarm: the editor compiles the morph's variants before the
// playhead reaches B); get() takes a prewarmed variant over, waiting for it if needed.
// Not thread-safe: one owner thread calls every member; only create() runs on other threads.
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <tuple>

#include <vulkan/vulkan.h>

#include "core/util/result.h"

namespace animorph::gpu {

struct FieldPipelines {
  VkPipeline blocks = VK_NULL_HANDLE, cells = VK_NULL_HANDLE, emit = VK_NULL_HANDLE, normals = VK_NULL_HANDLE;
};

// (features, kinds, storage pool 0/1).
using FieldVariantKey = std::tuple<uint32_t, uint32_t, int>;

class FieldPipelineCache {
 public:
  // Creates a variant's pipelines; must be safe to call on any thread (it touches only the
  // device and the pipeline layout).
  using Create = std::function<Result<FieldPipelines>(const FieldVariantKey&)>;
  explicit FieldPipelineCache(Create create) : create_(std::move(create)) {}

  // The variant's pipelines: cached, taken over from a prewarm, or created now. A failure is
  // not cached (the next call tries again).
  Result<FieldPipelines> get(const FieldVariantKey& key);
  // Starts compiling the variant on a background thread unless it is cached or compiling.
  void prewarm(const FieldVariantKey& key);
  // The variant can be had without waiting.
  bool ready(const FieldVariantKey& key) const;
  // Waits up to timeoutSec for every background compilation; false when one is still running.
  bool waitForCompilation(double timeoutSec) const;
  // Variants cached or compiling.
  size_t size() const { return variants_.size() + compiling_.size(); }

  // Waits for background compilations and keeps what they made (before the device is idled).
  void finishCompiling();
  // Destroys every cached pipeline (the device must be idle); the cache is empty afterwards.
  void destroy(VkDevice dev);

 private:
  Create create_;
  std::map<FieldVariantKey, FieldPipelines> variants_;
  std::map<FieldVariantKey, std::future<Result<FieldPipelines>>> compiling_;
};

}  // namespace animorph::gpu
