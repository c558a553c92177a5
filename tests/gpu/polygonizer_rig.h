#pragma once
// Shared set-up of the GPU polygoniser's tests: a test context (gpu_fixture.h: lavapipe, validation
// on) with a GpuPolygonizer on it, and a polygonisation read back.
#include <memory>

#include "core/poly/polygonizer.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/vulkan/context.h"

namespace animorph::test {

struct PolygonizerRig {
  std::unique_ptr<gpu::Context> ctx;
  std::unique_ptr<gpu::GpuPolygonizer> poly;
  // Makes the context and the polygoniser (REQUIREs both).
  PolygonizerRig();
  // poly->polygonize(f, s, prepared) and its read-back (REQUIREs both, naming the error); stats gets
  // the polygonisation's figures.
  TriangleMesh polygonizeAndRead(const gpu::GpuField& f, const gpu::GpuPolygonizeSettings& s,
                                 const gpu::GpuPreparedFrame* prepared, gpu::GpuPolygonizeStats& stats);
};

}  // namespace animorph::test
