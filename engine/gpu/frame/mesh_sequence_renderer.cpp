#include "gpu/frame/mesh_sequence_renderer.h"

#include "gpu/present/offscreen_target.h"
#include "gpu/render/mesh_cache.h"
#include "gpu/frame/scene_from_frame.h"
#include "gpu/render/scene_renderer.h"
#include "core/scene/mesh_character.h"
#include "gpu/vulkan/context.h"

namespace animorph::gpu {

Result<std::unique_ptr<MeshSequenceRenderer>> MeshSequenceRenderer::create(uint32_t width, uint32_t height,
                                                                           const ViewOptions& view) {
  std::unique_ptr<MeshSequenceRenderer> r(new MeshSequenceRenderer());
  r->width_ = width;
  r->height_ = height;
  r->view_ = view;
  r->view_.showSkeleton = false;
  auto ctx = Context::create(ContextSettings{});
  if (!ctx) return Error{"no usable Vulkan device: " + ctx.error()};
  r->ctx_ = std::move(*ctx);
  auto target = OffscreenTarget::create(*r->ctx_, width, height);
  if (!target) return Error{target.error()};
  r->target_ = std::move(*target);
  auto renderer = SceneRenderer::create(*r->ctx_, r->target_->renderPass());
  if (!renderer) return Error{renderer.error()};
  r->renderer_ = std::move(*renderer);
  r->cache_ = std::make_unique<MeshCache>(*r->ctx_);
  return r;
}

MeshSequenceRenderer::~MeshSequenceRenderer() {
  if (ctx_) ctx_->waitIdle();
}

void MeshSequenceRenderer::frameBounds(const Bounds& bounds) {
  camera_ = OrbitCamera{};
  camera_.yawRad = glm::radians(35.0f);
  camera_.pitchRad = glm::radians(20.0f);
  camera_.frame(bounds, float(width_) / float(height_));
}

Result<const RgbaImage*> MeshSequenceRenderer::render(const TriangleMesh& mesh) {
  SceneFrame frame;
  animorph::MeshDraw d;
  d.actorId = "morph";
  d.character = characterFromMesh(mesh, "baked");
  d.meshNode = 0;
  d.meshIndex = 0;
  d.joints = {glm::mat4(1.0f)};
  frame.meshes.push_back(d);
  Scene scene;
  buildScene(frame, view_, {}, *cache_, scene);
  const ViewportRect rect{0, 0, width_, height_};
  Status recorded = Status::success();
  Status st = target_->render(
      [&](VkCommandBuffer cmd) { recorded = renderer_->record(cmd, target_->serial(), rect, camera_, scene); },
      scene.options.background);
  cache_->endFrame();
  if (!st) return Error{st.error()};
  if (!recorded) return Error{recorded.error()};
  return &target_->image();
}

const std::string& MeshSequenceRenderer::deviceName() const { return ctx_->deviceName(); }

uint32_t MeshSequenceRenderer::validationErrors() const {
  return ctx_->validationEnabled() ? ctx_->validationErrorCount() : 0u;
}

}  // namespace animorph::gpu
