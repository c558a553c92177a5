#pragma once
// The meshes of a baked sequence drawn offscreen one at a time with one camera (PNG frames and
// playblasts). It owns a headless Vulkan context of its own, made on the thread that creates it:
// a background job may use it while the editor goes on drawing on its own device and queue
// (nothing is shared between the two).
#include <cstdint>
#include <memory>
#include <string>

#include "core/project/project.h"
#include "core/math/bounds.h"
#include "core/poly/mesh.h"
#include "gpu/present/rgba_image.h"
#include "core/util/result.h"
#include "core/camera/camera.h"

namespace animorph::gpu {

class Context;
class OffscreenTarget;
class SceneRenderer;
class MeshCache;

class MeshSequenceRenderer {
 public:
  // Errors: no usable Vulkan device ("no usable Vulkan device: ..."), what failed to be made.
  static Result<std::unique_ptr<MeshSequenceRenderer>> create(uint32_t width, uint32_t height,
                                                             const ViewOptions& view);
  ~MeshSequenceRenderer();

  // The camera framing all of bounds from 35 degrees of yaw and 20 of pitch (the sequence's
  // camera when the caller sets none).
  void frameBounds(const Bounds& bounds);
  void setCamera(const OrbitCamera& camera) { camera_ = camera; }

  // Draws mesh (world space) and returns the picture (valid until the next render).
  Result<const RgbaImage*> render(const TriangleMesh& mesh);

  const std::string& deviceName() const;
  // Validation errors counted on the context (0 without the validation layer).
  uint32_t validationErrors() const;
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  MeshSequenceRenderer() = default;
  uint32_t width_ = 0, height_ = 0;
  ViewOptions view_;
  OrbitCamera camera_;
  // Destroyed in reverse: the cache, the renderer and the target, then the device.
  std::unique_ptr<Context> ctx_;
  std::unique_ptr<OffscreenTarget> target_;
  std::unique_ptr<SceneRenderer> renderer_;
  std::unique_ptr<MeshCache> cache_;
};

}  // namespace animorph::gpu
