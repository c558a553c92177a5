#pragma once
// animorph-cli bake --gpu: the morph's B->C stage on the Vulkan compute polygoniser, plugged into
// the bake route as its implicit-stage polygoniser (export/project_frames.h), so the core needs no
// GPU. One device, its frames one at a time; the other stages stay on the CPU.
#include <memory>
#include <mutex>
#include <string>

#include "core/export/project_frames.h"
#include "core/util/result.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/vulkan/context.h"

namespace animorph::cli {

class GpuImplicitStage {
 public:
  // A Vulkan device and its polygoniser. Errors: no usable device, or the polygoniser cannot be
  // made on it (no silent fallback to the CPU).
  static Result<std::unique_ptr<GpuImplicitStage>> create();

  std::string deviceName() const { return context_->deviceName(); }
  // Validation errors the device reported so far (0 when validation is off).
  uint32_t validationErrors() const;
  // The polygoniser for BakeSettings::implicitStage; valid while this object lives.
  ImplicitStagePolygonizer polygonizer();

 private:
  // The B->C frame at timeSec, on the same field and grid as the CPU's.
  Result<MorphFrame> morphFrame(const MorphRuntime& rt, double timeSec, int resolution);

  std::unique_ptr<gpu::Context> context_;
  std::unique_ptr<gpu::GpuPolygonizer> polygonizer_;
  std::mutex mutex_;
};

}  // namespace animorph::cli
