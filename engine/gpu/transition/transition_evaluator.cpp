#include "gpu/transition/transition_evaluator.h"

#include <algorithm>
#include <cstring>

#include "core/rig/mesh_normals.h"
#include "gpu/vulkan/shader_module.h"
#include "shared_constants.h"
#include "transition_constants.h"
#include "gpu/transition/transition_params.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

namespace {

// std430 mirror of struct Vertex in transition.comp.glsl.
struct EvalVertex {
  glm::vec4 position, normal;
  glm::uvec4 joints0, joints1;
  glm::vec4 weights0, weights1;
};
static_assert(sizeof(EvalVertex) == 96);

// Push constants: mesh_push.glsl, with flags = vertex count.
struct EvalPush {
  glm::mat4 model;
  glm::vec4 color;
  uint32_t jointOffset, jointCount, vertexCount;
  float depthPull;
};
static_assert(sizeof(EvalPush) == 96);

}  // namespace

Result<std::unique_ptr<TransitionEvaluator>> TransitionEvaluator::create(Context& ctx) {
  std::unique_ptr<TransitionEvaluator> e(new TransitionEvaluator(ctx));
  Status s = e->init();
  if (!s) return Error{"transition evaluator: " + s.error()};
  return e;
}

Status TransitionEvaluator::init() {
  VkDevice dev = ctx_.device();
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  VkDescriptorSetLayoutBinding b0[4] = {
      {kBindingJoints, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr},
      {AM_TRE_BINDING_VERTICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr},
      {AM_TRE_BINDING_STANDIN, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr},
      {AM_TRE_BINDING_OUTPUT, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr}};
  VkDescriptorSetLayoutBinding b1 = {AM_TRANSITION_BINDING_PARAMS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 4;
  li.pBindings = b0;
  AM_VK_TRY(vkCreateDescriptorSetLayout(dev, &li, nullptr, &setLayouts_[0]), "vkCreateDescriptorSetLayout");
  li.bindingCount = 1;
  li.pBindings = &b1;
  AM_VK_TRY(vkCreateDescriptorSetLayout(dev, &li, nullptr, &setLayouts_[1]), "vkCreateDescriptorSetLayout");
  VkPushConstantRange push{cs, 0, sizeof(EvalPush)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 2;
  pli.pSetLayouts = setLayouts_;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &push;
  AM_VK_TRY(vkCreatePipelineLayout(dev, &pli, nullptr, &layout_), "vkCreatePipelineLayout");
  Result<VkShaderModule> sm = createShaderModule(dev, "transition.comp");
  if (!sm) return Error{sm.error()};
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, *sm, "main", nullptr};
  ci.layout = layout_;
  VkResult r = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
  vkDestroyShaderModule(dev, *sm, nullptr);
  if (r != VK_SUCCESS) return vkError("transition.comp pipeline", r);
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 5};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 2;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  AM_VK_TRY(vkCreateDescriptorPool(dev, &pi, nullptr, &pool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 2;
  ai.pSetLayouts = setLayouts_;
  AM_VK_TRY(vkAllocateDescriptorSets(dev, &ai, sets_), "vkAllocateDescriptorSets");
  const auto& limits = ctx_.properties().limits;
  if (limits.timestampComputeAndGraphics && limits.timestampPeriod > 0.0f) {
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = 2;
    if (vkCreateQueryPool(dev, &qi, nullptr, &queries_) != VK_SUCCESS) queries_ = VK_NULL_HANDLE;
  }
  return ensureHost(params_, sizeof(TransitionParams), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

TransitionEvaluator::~TransitionEvaluator() {
  VkDevice dev = ctx_.device();
  vkDeviceWaitIdle(dev);
  for (Buffer* b : {&vertices_, &joints_, &params_, &output_}) destroyBuffer(dev, *b);
  if (queries_) vkDestroyQueryPool(dev, queries_, nullptr);
  if (pipeline_) vkDestroyPipeline(dev, pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
  if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
  for (VkDescriptorSetLayout l : setLayouts_)
    if (l) vkDestroyDescriptorSetLayout(dev, l, nullptr);
}

Status TransitionEvaluator::ensureHost(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage) {
  size = std::max<VkDeviceSize>(size, 256);
  if (b.buffer && b.size >= size) return Status::success();
  vkDeviceWaitIdle(ctx_.device());
  destroyBuffer(ctx_.device(), b);
  Result<Buffer> nb = createHostBuffer(ctx_, size, usage);
  if (!nb) return Error{nb.error()};
  b = *nb;
  return Status::success();
}

Status TransitionEvaluator::setMesh(const Mesh& mesh, const GpuStandinBinding& binding, uint32_t firstVertex) {
  const size_t n = mesh.positions.size();
  if (n == 0) return Error{"mesh '" + mesh.name + "': no vertices"};
  if (size_t(firstVertex) + n > binding.vertexCount())
    return Error{"mesh '" + mesh.name + "': vertices " + std::to_string(firstVertex) + ".." +
                 std::to_string(firstVertex + n) + " beyond the stand-in binding's " +
                 std::to_string(binding.vertexCount())};
  const std::vector<glm::vec3> normals = mesh.normals.size() == n ? mesh.normals : computeAreaWeightedNormals(mesh.positions, mesh.indices);
  Status s = ensureHost(vertices_, n * sizeof(EvalVertex), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (s) s = ensureHost(output_, n * 2 * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!s) return s;
  auto clampJoints = [](const glm::uvec4& j) { return glm::min(j, glm::uvec4(0xffffu)); };
  auto* v = static_cast<EvalVertex*>(vertices_.mapped);
  for (size_t i = 0; i < n; ++i) {
    EvalVertex e{};
    e.position = glm::vec4(mesh.positions[i], 1.0f);
    e.normal = glm::vec4(normals[i], 0.0f);
    e.weights0 = glm::vec4(1, 0, 0, 0);
    if (!mesh.joints0.empty()) {
      e.joints0 = clampJoints(mesh.joints0[i]);
      e.weights0 = mesh.weights0[i];
    }
    if (!mesh.joints1.empty()) {
      e.joints1 = clampJoints(mesh.joints1[i]);
      e.weights1 = mesh.weights1[i];
    }
    v[i] = e;
  }
  vertexCount_ = uint32_t(n);
  standin_ = binding.buffer();
  standinOffset_ = VkDeviceSize(firstVertex) * GpuStandinBinding::kVertexStride;
  return Status::success();
}

Status TransitionEvaluator::evaluate(std::span<const glm::mat4> joints, const glm::mat4& model,
                                     const TransitionFrame& frame, std::vector<glm::vec3>& positions,
                                     std::vector<glm::vec3>& normals) {
  if (vertexCount_ == 0) return Error{"transition evaluator: no mesh set"};
  const glm::mat4 identity(1.0f);
  if (joints.empty()) joints = std::span<const glm::mat4>(&identity, 1);
  Status s = ensureHost(joints_, joints.size_bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!s) return s;
  std::memcpy(joints_.mapped, joints.data(), joints.size_bytes());
  packTransitionParams(frame, *static_cast<TransitionParams*>(params_.mapped));

  const VkDeviceSize n = vertexCount_;
  VkDescriptorBufferInfo infos[5] = {{joints_.buffer, 0, VK_WHOLE_SIZE},
                                     {vertices_.buffer, 0, n * sizeof(EvalVertex)},
                                     {standin_, standinOffset_, n * GpuStandinBinding::kVertexStride},
                                     {output_.buffer, 0, n * 2 * sizeof(glm::vec4)},
                                     {params_.buffer, 0, sizeof(TransitionParams)}};
  const uint32_t bindings[5] = {kBindingJoints, AM_TRE_BINDING_VERTICES, AM_TRE_BINDING_STANDIN, AM_TRE_BINDING_OUTPUT,
                                AM_TRANSITION_BINDING_PARAMS};
  VkWriteDescriptorSet w[5]{};
  for (int k = 0; k < 5; ++k)
    w[k] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, sets_[k == 4 ? 1 : 0], bindings[k], 0, 1,
            VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &infos[k], nullptr};
  vkUpdateDescriptorSets(ctx_.device(), 5, w, 0, nullptr);

  EvalPush push{};
  push.model = model;
  push.jointOffset = 0;
  push.jointCount = uint32_t(joints.size());
  push.vertexCount = vertexCount_;
  s = ctx_.submitImmediate([&](VkCommandBuffer cmd) {
    if (queries_) {
      vkCmdResetQueryPool(cmd, queries_, 0, 2);
      vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 2, sets_, 0, nullptr);
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, (vertexCount_ + AM_TRE_WORKGROUP - 1) / AM_TRE_WORKGROUP, 1, 1);
    if (queries_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr,
                         0, nullptr);
  });
  if (!s) return s;
  lastDispatchMs_ = 0.0;
  if (queries_) {
    uint64_t t[2] = {0, 0};
    if (vkGetQueryPoolResults(ctx_.device(), queries_, 0, 2, sizeof(t), t, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) == VK_SUCCESS)
      lastDispatchMs_ = double(t[1] - t[0]) * ctx_.properties().limits.timestampPeriod * 1e-6;
  }
  const auto* out = static_cast<const glm::vec4*>(output_.mapped);
  positions.resize(n);
  normals.resize(n);
  for (size_t i = 0; i < n; ++i) {
    positions[i] = glm::vec3(out[2 * i]);
    normals[i] = glm::vec3(out[2 * i + 1]);
  }
  return Status::success();
}

}  // namespace animorph::gpu
