#pragma once
// The GPU transition (shaders/include/transition.glsl, the code transition.vert
// runs) evaluated by a compute shader with the world positions and normals read
// back: how the tests compare the shader with the CPU transition
// (standin_morph/transition.h evaluateTransition), and what `bench morph` times.
// Not for the frame loop (it waits for the GPU).
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "gpu/transition/gpu_standin_binding.h"
#include "core/scene/transition_frame.h"
#include "core/rig/character.h"

namespace animorph::gpu {

class TransitionEvaluator {
 public:
  // The compute pipeline. Errors: Vulkan failures.
  static Result<std::unique_ptr<TransitionEvaluator>> create(Context& ctx);
  ~TransitionEvaluator();
  TransitionEvaluator(const TransitionEvaluator&) = delete;
  TransitionEvaluator& operator=(const TransitionEvaluator&) = delete;

  // Uploads mesh (as GpuMesh does: missing normals computed, joint indices
  // beyond u16 ignored) and uses binding's vertices from firstVertex on.
  // Errors: binding too short for the mesh, Vulkan failures.
  Status setMesh(const Mesh& mesh, const GpuStandinBinding& binding, uint32_t firstVertex);

  // Evaluates every vertex of the mesh with joint matrices joints (rig/pose.h
  // jointMatrices; empty: one identity), model matrix and frame parameters;
  // world positions and unit normals come back. Errors: no mesh set, Vulkan failures.
  Status evaluate(std::span<const glm::mat4> joints, const glm::mat4& model, const TransitionFrame& frame,
                  std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

  // GPU time of the last evaluate's dispatch (timestamps), in ms; 0 when the
  // queue has no timestamps.
  double lastDispatchMs() const { return lastDispatchMs_; }

 private:
  explicit TransitionEvaluator(Context& ctx) : ctx_(ctx) {}
  Status init();
  Status ensureHost(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage);

  Context& ctx_;
  VkDescriptorSetLayout setLayouts_[2]{};
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet sets_[2]{};
  VkQueryPool queries_ = VK_NULL_HANDLE;
  Buffer vertices_, joints_, params_, output_;
  VkBuffer standin_ = VK_NULL_HANDLE;
  VkDeviceSize standinOffset_ = 0;
  uint32_t vertexCount_ = 0;
  double lastDispatchMs_ = 0.0;
};

}  // namespace animorph::gpu
