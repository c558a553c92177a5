#include "gpu/render/scene_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/graphics_pipeline.h"
#include "gpu/vulkan/shader_module.h"
#include "shared_constants.h"
#include "transition_constants.h"
#include "gpu/transition/transition_params.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

// Push constants of the mesh pipelines (shaders/include/mesh_push.glsl); line.vert reads the first 64 bytes as LinePush.
struct MeshPush {
  glm::mat4 model;
  glm::vec4 color;
  uint32_t jointOffset;
  uint32_t jointCount;
  uint32_t flags;
  float depthPull;
  glm::vec4 baseLinear;  // rgb: color.rgb in linear light (the shaders would take it per pixel)
  uint32_t morphOffset;       // blend shapes: float index of the draw's (target, weight) pairs in the joint buffer
  uint32_t morphCount;        // active targets; 0: none
  uint32_t morphVertexCount;  // the mesh's vertices
  uint32_t morphPad;
};
static_assert(sizeof(MeshPush) == 128);  // the 128 bytes every device has (lavapipe's maxPushConstantsSize)

namespace {

// std140 mirror of FrameUniforms in shaders/include/frame.glsl.
struct FrameUniforms {
  glm::mat4 viewProj;
  glm::mat4 view;
  glm::vec4 cameraPos;
  glm::vec4 keyLightDir;
  glm::vec4 grid;
  glm::vec4 gridCenter;
  glm::vec4 selectColor;
  glm::vec4 viewportPx;
};
static_assert(sizeof(FrameUniforms) == 2 * 64 + 6 * 16);


// The colour's rgb in linear light, as the viewport shading uses it (gamma 2.2).
glm::vec4 linearRgb(const glm::vec4& c) {
  return glm::vec4(glm::pow(glm::clamp(glm::vec3(c), 0.0f, 1.0f), glm::vec3(2.2f)), c.a);
}
constexpr VkShaderStageFlags kPushStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

// Clip-space depth pulled toward the camera by the wireframe pass (in NDC depth units).
constexpr float kWireDepthPull = 5e-5f;

enum class VertexInput { None, Mesh, MeshWeights, Line, Generated, Transition, Sphere };

// A particle in the frame's ring buffer: its sphere (vec4), then, after all of its draw's spheres,
// its colour (RGBA8).
constexpr VkDeviceSize kParticleBytes = sizeof(glm::vec4) + sizeof(uint32_t);

struct PipelineDesc {
  const char* vert;
  const char* frag;
  VertexInput input;
  VkPrimitiveTopology topology;
  VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
  bool depthTest = true;
  bool depthWrite = true;
  bool blend = false;
  VkCullModeFlags cull = VK_CULL_MODE_NONE;
  bool standinColor = true;  // AM_SPEC_STANDIN_COLOR of the transition and material shaders
};

Result<VkPipeline> createPipeline(VkDevice device, VkRenderPass pass, VkPipelineLayout layout, const PipelineDesc& d) {
  GraphicsPipelineDesc g;
  g.vert = d.vert;
  g.frag = d.frag;
  const VkBool32 standinColor = d.standinColor ? VK_TRUE : VK_FALSE;
  const VkSpecializationMapEntry specEntry{AM_SPEC_STANDIN_COLOR, 0, sizeof(VkBool32)};
  const VkSpecializationInfo spec{1, &specEntry, sizeof standinColor, &standinColor};
  if (d.input == VertexInput::Transition) g.specialization = &spec;
  std::vector<VkVertexInputBindingDescription>& bindings = g.bindings;
  std::vector<VkVertexInputAttributeDescription>& attributes = g.attributes;
  if (d.input == VertexInput::Mesh || d.input == VertexInput::MeshWeights || d.input == VertexInput::Transition) {
    const struct { uint32_t stride; VkFormat format; } streams[6] = {
        {12, VK_FORMAT_R32G32B32_SFLOAT}, {12, VK_FORMAT_R32G32B32_SFLOAT}, {8, VK_FORMAT_R16G16B16A16_UINT},
        {8, VK_FORMAT_R16G16B16A16_UINT}, {16, VK_FORMAT_R32G32B32A32_SFLOAT}, {16, VK_FORMAT_R32G32B32A32_SFLOAT}};
    for (uint32_t s = 0; s < 6; ++s) {
      bindings.push_back({s, streams[s].stride, VK_VERTEX_INPUT_RATE_VERTEX});
      attributes.push_back({s, s, streams[s].format, 0});
    }
    if (d.input != VertexInput::MeshWeights) {  // the material streams (include/material_vertex.glsl)
      bindings.push_back({kVertexTexcoord0, 8, VK_VERTEX_INPUT_RATE_VERTEX});
      attributes.push_back({kVertexTexcoord0, kVertexTexcoord0, VK_FORMAT_R32G32_SFLOAT, 0});
      bindings.push_back({kVertexColor0, 16, VK_VERTEX_INPUT_RATE_VERTEX});
      attributes.push_back({kVertexColor0, kVertexColor0, VK_FORMAT_R32G32B32A32_SFLOAT, 0});
    }
    if (d.input == VertexInput::Transition) {  // the stand-in binding: (dp, m), (n~, 0) interleaved
      bindings.push_back({AM_VERTEX_STANDIN_OFFSET, uint32_t(GpuStandinBinding::kVertexStride), VK_VERTEX_INPUT_RATE_VERTEX});
      attributes.push_back({AM_VERTEX_STANDIN_OFFSET, AM_VERTEX_STANDIN_OFFSET, VK_FORMAT_R32G32B32A32_SFLOAT, 0});
      attributes.push_back({AM_VERTEX_STANDIN_NORMAL, AM_VERTEX_STANDIN_OFFSET, VK_FORMAT_R32G32B32A32_SFLOAT, 16});
    }
    if (d.input == VertexInput::MeshWeights) {
      bindings.push_back({kVertexPaintWeight, 4, VK_VERTEX_INPUT_RATE_VERTEX});
      attributes.push_back({kVertexPaintWeight, kVertexPaintWeight, VK_FORMAT_R32_SFLOAT, 0});
    }
  } else if (d.input == VertexInput::Generated) {
    for (uint32_t s = 0; s < 2; ++s) {  // AM_VERTEX_POSITION, AM_VERTEX_NORMAL (w: the colour pass's colour)
      bindings.push_back({s, GeneratedMeshDraw::kVertexStride, VK_VERTEX_INPUT_RATE_VERTEX});
      attributes.push_back({s, s, s == 1 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32G32B32_SFLOAT, 0});
    }
  } else if (d.input == VertexInput::Sphere) {  // per instance: a vec4 (centre, radius), an RGBA8 colour
    bindings.push_back({0, sizeof(glm::vec4), VK_VERTEX_INPUT_RATE_INSTANCE});
    attributes.push_back({0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0});
    bindings.push_back({1, sizeof(uint32_t), VK_VERTEX_INPUT_RATE_INSTANCE});
    attributes.push_back({1, 1, VK_FORMAT_R8G8B8A8_UNORM, 0});
  } else if (d.input == VertexInput::Line) {
    bindings.push_back({0, sizeof(LineVertex), VK_VERTEX_INPUT_RATE_VERTEX});
    attributes.push_back({0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0});
    attributes.push_back({1, 0, VK_FORMAT_R8G8B8A8_UNORM, 12});
  }
  g.topology = d.topology;
  g.polygonMode = d.polygonMode;
  g.depthTest = d.depthTest;
  g.depthWrite = d.depthWrite;
  g.blend = d.blend ? BlendMode::OverOpaque : BlendMode::None;
  g.cull = d.cull;
  return createGraphicsPipeline(device, pass, layout, g);
}

}  // namespace

// Per-frame data of one frame in flight. Each record() call of a frame appends
// to the buffers; a buffer that must grow mid-frame is retired (commands recorded
// earlier in the frame still read it) and freed when the slot is next rewound.
struct SceneRenderer::Slot {
  uint64_t serial = UINT64_MAX;  // frame whose data the slot holds
  Buffer frame;                  // FrameUniforms records at uniformStride_ (dynamic offset)
  Buffer joints;                 // mat4 per joint of every draw
  Buffer lines;                  // LineVertex
  Buffer weights;                // float per vertex of every weight overlay
  Buffer particles;              // vec4 (centre, radius) per particle of every particle draw
  VkDeviceSize frameUsed = 0, jointsUsed = 0, linesUsed = 0, weightsUsed = 0, particlesUsed = 0;
  VkDescriptorSet set = VK_NULL_HANDLE;  // frame + joints
  bool setBound = false;                 // set is referenced by commands of this frame
  Buffer transitionParams;               // TransitionParams records at transitionParamStride_ (dynamic offset)
  VkDeviceSize transitionParamsUsed = 0;
  VkDescriptorSet transitionSet = VK_NULL_HANDLE;  // set 1 of the transition pipelines
  bool transitionSetBound = false;
  std::vector<Buffer> retiredBuffers;
  std::vector<VkDescriptorSet> retiredSets;
};

SceneRenderer::SceneRenderer(Context& ctx) : ctx_(ctx) {}

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(Context& ctx, VkRenderPass renderPass,
                                                             SceneRendererSettings settings) {
  std::unique_ptr<SceneRenderer> r(new SceneRenderer(ctx));
  Status s = r->init(renderPass, settings);
  if (!s) return Error{"scene renderer: " + s.error()};
  return r;
}

Status SceneRenderer::init(VkRenderPass renderPass, SceneRendererSettings settings) {
  edgeListWireframe_ = settings.forceEdgeListWireframe || !ctx_.supportsWireframeFill();
  if (Status s = createLayouts(); !s) return s;
  if (Status s = createDescriptorPool(); !s) return s;
  if (Status s = createPipelines(renderPass); !s) return s;
  if (Status st = initMorphPlaceholder(); !st) return st;
  TextureImage white;
  white.name = "white placeholder";
  white.width = white.height = 1;
  white.rgba = std::make_shared<const std::vector<uint8_t>>(4, uint8_t(255));
  Result<std::unique_ptr<GpuTexture>> whiteTex = GpuTexture::upload(ctx_, white);
  if (!whiteTex) return Error{whiteTex.error()};
  whiteTexture_ = std::move(*whiteTex);
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    slots_.push_back(std::make_unique<Slot>());
    Status s = reserve(*slots_.back(), 0, 0);  // initial capacity: steady frames allocate nothing
    if (!s) return s;
  }
  return Status::success();
}

// The descriptor set layouts (frame + joints, the transitions' parameters, blend shapes, material)
// and the two pipeline layouts over all four.
Status SceneRenderer::createLayouts() {
  VkDevice dev = ctx_.device();
  VkDescriptorSetLayoutBinding b[2]{};
  b[0] = {kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  b[1] = {kBindingJoints, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo sli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  sli.bindingCount = 2;
  sli.pBindings = b;
  AM_VK_TRY(vkCreateDescriptorSetLayout(dev, &sli, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
  // Set 1 of the transition pipelines: the per-draw TransitionParams.
  VkDescriptorSetLayoutBinding tb{AM_TRANSITION_BINDING_PARAMS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 1,
                                  VK_SHADER_STAGE_VERTEX_BIT, nullptr};
  sli.bindingCount = 1;
  sli.pBindings = &tb;
  AM_VK_TRY(vkCreateDescriptorSetLayout(dev, &sli, nullptr, &transitionSetLayout_), "vkCreateDescriptorSetLayout");
  // Set 2 (AM_MORPH_SET): a mesh's blend-shape deltas (render/gpu_mesh.h).
  Result<VkDescriptorSetLayout> morphLayout = createMorphSetLayout(dev);
  if (!morphLayout) return Error{morphLayout.error()};
  morphSetLayout_ = *morphLayout;
  // Set 3 (AM_MATERIAL_SET): a part's base colour texture (render/gpu_texture.h).
  Result<VkDescriptorSetLayout> materialLayout = createMaterialSetLayout(dev);
  if (!materialLayout) return Error{materialLayout.error()};
  materialSetLayout_ = *materialLayout;
  // Both layouts hold all four sets, so they agree on every set and the push
  // constants: sets bound through one stay bound for pipelines of the other.
  VkPushConstantRange push{kPushStages, 0, sizeof(MeshPush)};
  const VkDescriptorSetLayout sets[4] = {setLayout_, transitionSetLayout_, morphSetLayout_, materialSetLayout_};
  static_assert(AM_TRANSITION_SET == 1 && AM_MORPH_SET == 2 && AM_MATERIAL_SET == 3, "set order of the pipeline layouts");
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 4;
  pli.pSetLayouts = sets;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &push;
  AM_VK_TRY(vkCreatePipelineLayout(dev, &pli, nullptr, &layout_), "vkCreatePipelineLayout");
  AM_VK_TRY(vkCreatePipelineLayout(dev, &pli, nullptr, &transitionLayout_), "vkCreatePipelineLayout");
  const VkDeviceSize storageAlign = std::max<VkDeviceSize>(ctx_.properties().limits.minStorageBufferOffsetAlignment, 16);
  transitionParamStride_ = (sizeof(TransitionParams) + storageAlign - 1) / storageAlign * storageAlign;
  return Status::success();
}

Status SceneRenderer::createDescriptorPool() {
  VkDevice dev = ctx_.device();
  // Sets are replaced only when a ring buffer grows: a few per slot over a session.
  constexpr uint32_t kMaxSets = 64;
  VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, kMaxSets},
                                   {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kMaxSets},
                                   {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, kMaxSets}};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  dpi.maxSets = 2 * kMaxSets;
  dpi.poolSizeCount = 3;
  dpi.pPoolSizes = sizes;
  AM_VK_TRY(vkCreateDescriptorPool(dev, &dpi, nullptr, &descriptorPool_), "vkCreateDescriptorPool");
  const VkDeviceSize align = std::max<VkDeviceSize>(ctx_.properties().limits.minUniformBufferOffsetAlignment, 16);
  uniformStride_ = (sizeof(FrameUniforms) + align - 1) / align * align;
  return Status::success();
}

// Every pipeline the renderer draws with (mesh, dithered, transition, wireframe, generated,
// overlays), on renderPass.
Status SceneRenderer::createPipelines(VkRenderPass renderPass) {
  VkDevice dev = ctx_.device();
  const VkCullModeFlags back = VK_CULL_MODE_BACK_BIT, none = VK_CULL_MODE_NONE;
  auto meshDesc = [](VkCullModeFlags cull) {
    PipelineDesc d{"mesh.vert", "mesh_material.frag", VertexInput::Mesh, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    d.cull = cull;
    return d;
  };
  auto wireDesc = [&](VkCullModeFlags cull) {
    PipelineDesc d = meshDesc(cull);
    // mesh_material.frag too (mesh.frag would leave the material outputs unread): with
    // AM_DRAW_WIREFRAME it draws the flat wire colour.
    if (edgeListWireframe_) {
      d.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;  // lines are never culled
      d.cull = none;
    } else {
      d.polygonMode = VK_POLYGON_MODE_LINE;
    }
    return d;
  };
  auto withShaders = [](PipelineDesc d, const char* vert, const char* frag, VertexInput input) {
    d.vert = vert;
    d.frag = frag;
    d.input = input;
    return d;
  };
  // A transition pipeline for draws with stand-in colours (coloured) or without (none to fade into).
  auto transitionDesc = [&](PipelineDesc d, const char* frag, bool coloured) {
    d = withShaders(d, "transition.vert", frag, VertexInput::Transition);
    d.standinColor = coloured;
    return d;
  };
  struct Want {
    VkPipeline* out;
    PipelineDesc desc;
    VkPipelineLayout layout = VK_NULL_HANDLE;  // null: layout_
  } wants[] = {
      {&meshPipeline_[0], meshDesc(back)},
      {&meshPipeline_[1], meshDesc(none)},
      {&meshDitherPipeline_[0], withShaders(meshDesc(back), "mesh.vert", "mesh_material_dither.frag", VertexInput::Mesh)},
      {&generatedDitherPipeline_, withShaders(meshDesc(back), "generated.vert", "generated_dither.frag", VertexInput::Generated)},
      {&meshDitherPipeline_[1], withShaders(meshDesc(none), "mesh.vert", "mesh_material_dither.frag", VertexInput::Mesh)},
      {&transitionPipeline_[0], transitionDesc(meshDesc(back), "mesh_material.frag", false), transitionLayout_},
      {&transitionPipeline_[1], transitionDesc(meshDesc(none), "mesh_material.frag", false), transitionLayout_},
      {&transitionDitherPipeline_[0], transitionDesc(meshDesc(back), "mesh_material_dither.frag", false), transitionLayout_},
      {&transitionDitherPipeline_[1], transitionDesc(meshDesc(none), "mesh_material_dither.frag", false), transitionLayout_},
      {&transitionColorPipeline_[0], transitionDesc(meshDesc(back), "mesh_material.frag", true), transitionLayout_},
      {&transitionColorPipeline_[1], transitionDesc(meshDesc(none), "mesh_material.frag", true), transitionLayout_},
      {&transitionColorDitherPipeline_[0], transitionDesc(meshDesc(back), "mesh_material_dither.frag", true), transitionLayout_},
      {&transitionColorDitherPipeline_[1], transitionDesc(meshDesc(none), "mesh_material_dither.frag", true), transitionLayout_},
      {&wirePipeline_[0], wireDesc(back)},
      {&wirePipeline_[1], wireDesc(none)},
      {&transitionWirePipeline_[0], transitionDesc(wireDesc(back), "mesh_material.frag", false), transitionLayout_},
      {&transitionWirePipeline_[1], transitionDesc(wireDesc(none), "mesh_material.frag", false), transitionLayout_},
      {&generatedPipeline_, {"generated.vert", "generated.frag", VertexInput::Generated, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                             VK_POLYGON_MODE_FILL, true, true, false, back}},
      {&weightPipeline_, {"weight_overlay.vert", "weight_overlay.frag", VertexInput::MeshWeights,
                          VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, VK_POLYGON_MODE_FILL, true, true, false, none}},
      {&particlePipeline_, {"particle_sphere.vert", "particle_sphere.frag", VertexInput::Sphere,
                            VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, VK_POLYGON_MODE_FILL, true, true, false, none}},
      {&gridPipeline_, {"grid.vert", "grid.frag", VertexInput::None, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                        VK_POLYGON_MODE_FILL, true, false, true}},
      {&linePipeline_, {"line.vert", "line.frag", VertexInput::Line, VK_PRIMITIVE_TOPOLOGY_LINE_LIST,
                        VK_POLYGON_MODE_FILL, true, true, true}},
      {&overlayPipeline_, {"line.vert", "line.frag", VertexInput::Line, VK_PRIMITIVE_TOPOLOGY_LINE_LIST,
                           VK_POLYGON_MODE_FILL, false, false, true}},
  };
  for (auto& w : wants) {
    Result<VkPipeline> p = createPipeline(dev, renderPass, w.layout ? w.layout : layout_, w.desc);
    if (!p) return Error{p.error()};
    *w.out = *p;
  }
  if (!edgeListWireframe_) {
    Result<VkPipeline> p = createPipeline(dev, renderPass, layout_,
                                          withShaders(wireDesc(back), "generated.vert", "generated.frag", VertexInput::Generated));
    if (!p) return Error{p.error()};
    generatedWirePipeline_ = *p;
  }

  return Status::success();
}

// The set bound for meshes without morph targets (their shader path never reads it).
Status SceneRenderer::initMorphPlaceholder() {
  const float zeros[kMorphDeltaFloats] = {};
  Result<Buffer> buf = createDeviceBuffer(ctx_, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, zeros, sizeof zeros);
  if (!buf) return Error{"morph placeholder: " + buf.error()};
  morphPlaceholder_ = *buf;
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = descriptorPool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &morphSetLayout_;
  AM_VK_TRY(vkAllocateDescriptorSets(ctx_.device(), &ai, &morphPlaceholderSet_), "vkAllocateDescriptorSets");
  VkDescriptorBufferInfo info{morphPlaceholder_.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, morphPlaceholderSet_, AM_MORPH_BINDING_DELTAS,
                         0, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &info, nullptr};
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
  return Status::success();
}

// Appends a draw's active blend shapes to the joint data as (target, weight)
// pairs, mat4-aligned (the shader reads the joint buffer as floats too): the
// non-zero weights of targets the device holds, at most kMaxActiveMorphTargets
// (those of largest |weight|), in target order as the CPU adds them.
void SceneRenderer::addMorphWeights(const GpuMesh* mesh, std::span<const float> weights) {
  DrawMorph dm;
  const size_t targets = mesh ? std::min<size_t>(weights.size(), mesh->morphTargetCount()) : 0;
  std::vector<std::pair<uint32_t, float>> active;
  for (size_t t = 0; t < targets; ++t)
    if (weights[t] != 0.0f && std::isfinite(weights[t])) active.push_back({uint32_t(t), weights[t]});
  if (active.size() > kMaxActiveMorphTargets) {
    std::nth_element(active.begin(), active.begin() + kMaxActiveMorphTargets, active.end(),
                     [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
    active.resize(kMaxActiveMorphTargets);
    std::sort(active.begin(), active.end());
  }
  if (!active.empty()) {
    dm.offset = static_cast<uint32_t>(jointScratch_.size() * 16);
    dm.count = static_cast<uint32_t>(active.size());
    std::vector<float> block((2 * active.size() + 15) / 16 * 16, 0.0f);
    for (size_t i = 0; i < active.size(); ++i) {
      std::memcpy(&block[2 * i], &active[i].first, sizeof(uint32_t));  // floatBitsToUint in the shader
      block[2 * i + 1] = active[i].second;
    }
    for (size_t k = 0; k < block.size(); k += 16) {
      glm::mat4 m;
      std::memcpy(&m[0][0], &block[k], 16 * sizeof(float));
      jointScratch_.push_back(m);
    }
  }
  drawMorphs_.push_back(dm);
}

SceneRenderer::~SceneRenderer() {
  VkDevice dev = ctx_.device();
  vkDeviceWaitIdle(dev);
  for (auto& s : slots_) {
    rewind(*s, UINT64_MAX);
    destroyBuffer(dev, s->frame);
    destroyBuffer(dev, s->joints);
    destroyBuffer(dev, s->lines);
    destroyBuffer(dev, s->weights);
    destroyBuffer(dev, s->particles);
    destroyBuffer(dev, s->transitionParams);
  }
  for (VkPipeline p : {meshPipeline_[0], meshPipeline_[1], wirePipeline_[0], wirePipeline_[1], generatedPipeline_, weightPipeline_, gridPipeline_,
                       linePipeline_, overlayPipeline_, meshDitherPipeline_[0], meshDitherPipeline_[1], generatedDitherPipeline_,
                       transitionPipeline_[0], transitionPipeline_[1], transitionDitherPipeline_[0],
                       transitionWirePipeline_[0], transitionWirePipeline_[1], generatedWirePipeline_,
                       transitionDitherPipeline_[1], particlePipeline_, transitionColorPipeline_[0],
                       transitionColorPipeline_[1], transitionColorDitherPipeline_[0], transitionColorDitherPipeline_[1]})
    if (p) vkDestroyPipeline(dev, p, nullptr);
  destroyBuffer(dev, morphPlaceholder_);
  whiteTexture_.reset();
  if (materialSetLayout_) vkDestroyDescriptorSetLayout(dev, materialSetLayout_, nullptr);
  if (morphSetLayout_) vkDestroyDescriptorSetLayout(dev, morphSetLayout_, nullptr);
  if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
  if (transitionLayout_) vkDestroyPipelineLayout(dev, transitionLayout_, nullptr);
  if (transitionSetLayout_) vkDestroyDescriptorSetLayout(dev, transitionSetLayout_, nullptr);
  if (descriptorPool_) vkDestroyDescriptorPool(dev, descriptorPool_, nullptr);  // frees the sets
  if (setLayout_) vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
}

void SceneRenderer::rewind(Slot& slot, uint64_t frameSerial) {
  VkDevice dev = ctx_.device();
  for (Buffer& b : slot.retiredBuffers) destroyBuffer(dev, b);
  slot.retiredBuffers.clear();
  if (!slot.retiredSets.empty())
    vkFreeDescriptorSets(dev, descriptorPool_, static_cast<uint32_t>(slot.retiredSets.size()), slot.retiredSets.data());
  slot.retiredSets.clear();
  slot.frameUsed = slot.jointsUsed = slot.linesUsed = slot.weightsUsed = slot.transitionParamsUsed = 0;
  slot.particlesUsed = 0;
  slot.setBound = false;
  slot.transitionSetBound = false;
  slot.serial = frameSerial;
}

Status SceneRenderer::reserve(Slot& slot, VkDeviceSize jointBytes, VkDeviceSize lineBytes, VkDeviceSize weightBytes,
                              VkDeviceSize particleBytes) {
  bool setStale = slot.set == VK_NULL_HANDLE;
  auto fit = [&](Buffer& b, VkDeviceSize& used, VkDeviceSize need, VkDeviceSize minimum, VkBufferUsageFlags usage,
                 const char* what) -> Status {
    if (b.buffer && used + need <= b.size) return Status::success();
    VkDeviceSize size = std::max({need, b.size * 2, minimum});
    Result<Buffer> nb = createHostBuffer(ctx_, size, usage);
    if (!nb) return Error{std::string(what) + " ring buffer: " + nb.error()};
    if (b.buffer) slot.retiredBuffers.push_back(b);  // may still be read by this frame's commands
    b = *nb;
    used = 0;
    return Status::success();
  };
  const VkBuffer oldFrame = slot.frame.buffer, oldJoints = slot.joints.buffer;
  Status s = fit(slot.frame, slot.frameUsed, uniformStride_, 16 * uniformStride_, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "frame uniform");
  if (s) s = fit(slot.joints, slot.jointsUsed, jointBytes, 256 * sizeof(glm::mat4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "joint matrix");
  if (s) s = fit(slot.lines, slot.linesUsed, lineBytes, 4096 * sizeof(LineVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "line");
  if (s && weightBytes) s = fit(slot.weights, slot.weightsUsed, weightBytes, 4096 * sizeof(float), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "weight");
  if (s && particleBytes)
    s = fit(slot.particles, slot.particlesUsed, particleBytes, 4096 * sizeof(glm::vec4), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
            "particle");
  if (!s) return s;
  setStale |= slot.frame.buffer != oldFrame || slot.joints.buffer != oldJoints;
  if (!setStale) return Status::success();
  // A set already bound by this frame's commands must not change: retire it and use a new one.
  VkDevice dev = ctx_.device();
  if (slot.set && slot.setBound) slot.retiredSets.push_back(slot.set);
  if (!slot.set || slot.setBound) {
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = descriptorPool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &setLayout_;
    AM_VK_TRY(vkAllocateDescriptorSets(dev, &ai, &slot.set), "vkAllocateDescriptorSets");
    slot.setBound = false;
  }
  VkDescriptorBufferInfo frameInfo{slot.frame.buffer, 0, sizeof(FrameUniforms)};
  VkDescriptorBufferInfo jointInfo{slot.joints.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w[2]{};
  w[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, slot.set, kBindingFrame, 0, 1,
          VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, nullptr, &frameInfo, nullptr};
  w[1] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, slot.set, kBindingJoints, 0, 1,
          VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &jointInfo, nullptr};
  vkUpdateDescriptorSets(dev, 2, w, 0, nullptr);
  return Status::success();
}

Status SceneRenderer::reserveTransitionParams(Slot& slot, VkDeviceSize bytes) {
  if (slot.transitionParams.buffer && slot.transitionParamsUsed + bytes <= slot.transitionParams.size &&
      slot.transitionSet)
    return Status::success();
  VkDevice dev = ctx_.device();
  if (!slot.transitionParams.buffer || slot.transitionParamsUsed + bytes > slot.transitionParams.size) {
    const VkDeviceSize size = std::max({bytes, slot.transitionParams.size * 2, 4 * transitionParamStride_});
    Result<Buffer> nb = createHostBuffer(ctx_, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!nb) return Error{"transition parameter ring buffer: " + nb.error()};
    if (slot.transitionParams.buffer) slot.retiredBuffers.push_back(slot.transitionParams);
    slot.transitionParams = *nb;
    slot.transitionParamsUsed = 0;
    if (slot.transitionSet && slot.transitionSetBound) slot.retiredSets.push_back(slot.transitionSet);
    if (slot.transitionSet && !slot.transitionSetBound) vkFreeDescriptorSets(dev, descriptorPool_, 1, &slot.transitionSet);
    slot.transitionSet = VK_NULL_HANDLE;
  }
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = descriptorPool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &transitionSetLayout_;
  AM_VK_TRY(vkAllocateDescriptorSets(dev, &ai, &slot.transitionSet), "vkAllocateDescriptorSets");
  slot.transitionSetBound = false;
  VkDescriptorBufferInfo info{slot.transitionParams.buffer, 0, sizeof(TransitionParams)};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, slot.transitionSet, AM_TRANSITION_BINDING_PARAMS,
                         0, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, nullptr, &info, nullptr};
  vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
  return Status::success();
}

namespace {

// Cross-fading draws (opacity < 1) are dithered: colour alpha carries the opacity.
template <class Draw>
uint32_t fadeFlags(const Draw& d) {
  if (!(d.opacity < 1.0f)) return 0u;
  return AM_DRAW_DITHER | (d.complementDither ? AM_DRAW_DITHER_INVERT : 0u);
}

template <class Draw>
glm::vec4 fadeColor(const Draw& d) {
  return d.opacity < 1.0f ? glm::vec4(glm::vec3(d.color), std::max(0.0f, d.opacity)) : d.color;
}

}  // namespace

// One record() call: the command buffer, the slot, this call's places in the slot's buffers, and
// what is bound (pipelines and the morph set are rebound only when they change).
struct SceneRenderer::RecordPass {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  Slot* slot = nullptr;
  uint32_t frameOffset = 0;  // bytes into the frame uniforms
  uint32_t jointBase = 0;    // matrices into the joint buffer
  VkDeviceSize lineOffset = 0, weightBase = 0, particleBase = 0;  // bytes
  std::vector<VkDeviceSize> weightOffsets;  // per overlay, in bytes from weightBase
  uint32_t depthLineCount = 0, overlayLineCount = 0, axisFirst = 0;  // line vertices
  glm::mat4 viewProj{1.0f}, view{1.0f};
  uint32_t gridLines = 0;
  VkViewport viewport{};
  VkPipeline bound = VK_NULL_HANDLE;
  VkDescriptorSet boundMorphSet = VK_NULL_HANDLE;
  VkDescriptorSet boundMaterialSet = VK_NULL_HANDLE;
};

void SceneRenderer::gatherFrameData(const Scene& scene, RecordPass& rp) {
  // Joint matrices of every draw, then every line vertex (depth-tested lines, overlay lines, the
  // axis tripod).
  jointScratch_.clear();
  std::vector<uint32_t>& jointOffsets = drawJointOffsets_;
  jointOffsets.clear();
  drawMorphs_.clear();
  auto addJoints = [&](const MeshDraw& d) {
    jointOffsets.push_back(static_cast<uint32_t>(jointScratch_.size()));
    if (d.jointMatrices.empty()) jointScratch_.push_back(glm::mat4(1.0f));
    else jointScratch_.insert(jointScratch_.end(), d.jointMatrices.begin(), d.jointMatrices.end());
    addMorphWeights(d.mesh, d.morphWeights);
  };
  for (const MeshDraw& d : scene.meshes) addJoints(d);
  weightScratch_.clear();
  for (const WeightOverlayDraw& d : scene.weightOverlays) {
    jointOffsets.push_back(static_cast<uint32_t>(jointScratch_.size()));
    if (d.jointMatrices.empty()) jointScratch_.push_back(glm::mat4(1.0f));
    else jointScratch_.insert(jointScratch_.end(), d.jointMatrices.begin(), d.jointMatrices.end());
    addMorphWeights(d.mesh, d.morphWeights);
    rp.weightOffsets.push_back(weightScratch_.size() * sizeof(float));
    if (d.mesh && d.weights.size() == d.mesh->vertexCount())
      weightScratch_.insert(weightScratch_.end(), d.weights.begin(), d.weights.end());
  }
  for (const TransitionMeshDraw& t : scene.transitionMeshes) addJoints(t.draw);  // after the overlays'
  lineScratch_.clear();
  const auto& depthLines = scene.lines.vertices();
  const auto& overlayLines = scene.overlay.vertices();
  lineScratch_.insert(lineScratch_.end(), depthLines.begin(), depthLines.end());
  lineScratch_.insert(lineScratch_.end(), overlayLines.begin(), overlayLines.end());
  rp.depthLineCount = static_cast<uint32_t>(depthLines.size());
  rp.overlayLineCount = static_cast<uint32_t>(overlayLines.size());
  rp.axisFirst = static_cast<uint32_t>(lineScratch_.size());
  const glm::vec4 axisColors[3] = {{0.9f, 0.3f, 0.3f, 1}, {0.4f, 0.85f, 0.35f, 1}, {0.35f, 0.55f, 1.0f, 1}};
  for (int a = 0; a < 3; ++a) {
    glm::vec3 tip(0.0f);
    tip[a] = 1.0f;
    lineScratch_.push_back({glm::vec3(0.0f), packRgba(axisColors[a])});
    lineScratch_.push_back({tip, packRgba(axisColors[a])});
  }
}

Status SceneRenderer::uploadFrameData(const Scene& scene, RecordPass& rp) {
  Slot& slot = *rp.slot;
  const VkDeviceSize jointBytes = jointScratch_.size() * sizeof(glm::mat4);
  const VkDeviceSize lineBytes = lineScratch_.size() * sizeof(LineVertex);
  const VkDeviceSize weightBytes = weightScratch_.size() * sizeof(float);
  VkDeviceSize particleBytes = 0;
  for (const ParticleSpheresDraw& d : scene.particles) particleBytes += d.spheres.size() * kParticleBytes;
  Status cap = reserve(slot, jointBytes, lineBytes, weightBytes, particleBytes);
  if (cap && !scene.transitionMeshes.empty())
    cap = reserveTransitionParams(slot, scene.transitionMeshes.size() * transitionParamStride_);
  if (!cap) return cap;
  // This call's places in the slot's buffers.
  rp.frameOffset = static_cast<uint32_t>(slot.frameUsed);
  rp.jointBase = static_cast<uint32_t>(slot.jointsUsed / sizeof(glm::mat4));
  rp.lineOffset = slot.linesUsed;
  rp.weightBase = slot.weightsUsed;
  if (weightBytes)
    std::memcpy(static_cast<uint8_t*>(slot.weights.mapped) + rp.weightBase, weightScratch_.data(), weightBytes);
  slot.weightsUsed += weightBytes;
  rp.particleBase = slot.particlesUsed;
  for (const ParticleSpheresDraw& d : scene.particles) {  // each draw's spheres, then their colours
    uint8_t* at = static_cast<uint8_t*>(slot.particles.mapped) + slot.particlesUsed;
    const size_t n = d.spheres.size();
    std::memcpy(at, d.spheres.data(), n * sizeof(glm::vec4));
    if (d.colors.size() == n) std::memcpy(at + n * sizeof(glm::vec4), d.colors.data(), n * sizeof(uint32_t));
    else std::memset(at + n * sizeof(glm::vec4), 0, n * sizeof(uint32_t));  // alpha 0: the draw's colour
    slot.particlesUsed += n * kParticleBytes;
  }
  if (jointBytes)
    std::memcpy(static_cast<uint8_t*>(slot.joints.mapped) + slot.jointsUsed, jointScratch_.data(), jointBytes);
  if (lineBytes) std::memcpy(static_cast<uint8_t*>(slot.lines.mapped) + rp.lineOffset, lineScratch_.data(), lineBytes);
  slot.frameUsed += uniformStride_;
  slot.jointsUsed += jointBytes;
  slot.linesUsed += lineBytes;
  return Status::success();
}

void SceneRenderer::writeFrameUniforms(const ViewportRect& rect, const OrbitCamera& camera, const SceneOptions& opt,
                                       RecordPass& rp) {
  const float aspect = float(rect.width) / float(rect.height);
  rp.viewProj = camera.viewProjection(aspect);
  FrameUniforms fu{};
  fu.viewProj = rp.viewProj;
  fu.view = camera.view();
  rp.view = fu.view;
  fu.cameraPos = glm::vec4(camera.eye(), 1.0f);
  // Key light from the upper left, slightly behind the viewer (camera-relative like Maya's default light).
  fu.keyLightDir = glm::vec4(glm::normalize(-0.5f * camera.right() + 0.75f * camera.up() - 0.45f * camera.forward()), 0);
  const float cell = std::max(opt.gridCellM, 1e-4f);
  const float fadeEnd = std::max(20.0f * cell, 8.0f * camera.distanceM);
  fu.grid = glm::vec4(cell, 0.25f * fadeEnd, fadeEnd, fadeEnd);
  const float snap = 10.0f * cell;
  // The lines within the fade radius of the camera's foot (at most a camera distance from the target).
  const float gridHalf = fadeEnd + camera.distanceM + snap;
  rp.gridLines = static_cast<uint32_t>(std::min(std::ceil(gridHalf / cell), 2000.0f));
  fu.gridCenter = glm::vec4(std::round(camera.target.x / snap) * snap, 0.0f, std::round(camera.target.z / snap) * snap,
                            float(rp.gridLines));
  fu.selectColor = linearRgb(opt.selectColor);
  fu.viewportPx = glm::vec4(float(rect.width), float(rect.height),
                            0.5f * float(rect.height) / std::tan(0.5f * camera.fovYRad), 0.0f);
  std::memcpy(static_cast<uint8_t*>(rp.slot->frame.mapped) + rp.frameOffset, &fu, sizeof(fu));
}

void SceneRenderer::beginViewport(const ViewportRect& rect, const SceneOptions& opt, RecordPass& rp) {
  VkCommandBuffer cmd = rp.cmd;
  rp.viewport = VkViewport{float(rect.x), float(rect.y), float(rect.width), float(rect.height), 0.0f, 1.0f};
  VkRect2D scissor{{rect.x, rect.y}, {rect.width, rect.height}};
  vkCmdSetViewport(cmd, 0, 1, &rp.viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  VkClearAttachment clears[2]{};
  clears[0].aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
  clears[0].colorAttachment = 0;
  clears[0].clearValue.color = {{opt.background.r, opt.background.g, opt.background.b, opt.background.a}};
  clears[1].aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
  clears[1].clearValue.depthStencil = {1.0f, 0};
  VkClearRect clearRect{scissor, 0, 1};
  vkCmdClearAttachments(cmd, 2, clears, 1, &clearRect);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &rp.slot->set, 1, &rp.frameOffset);
  rp.slot->setBound = true;
}

void SceneRenderer::bindPipeline(RecordPass& rp, VkPipeline p) {
  if (p != rp.bound) vkCmdBindPipeline(rp.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
  rp.bound = p;
}

void SceneRenderer::setMorph(RecordPass& rp, MeshPush& p, const GpuMesh* mesh, size_t i) {
  const DrawMorph& dm = drawMorphs_[i];
  p.morphOffset = rp.jointBase * 16u + dm.offset;
  p.morphCount = dm.count;
  p.morphVertexCount = mesh ? mesh->vertexCount() : 0u;
  // Set 2: the mesh's blend-shape deltas, or the placeholder; rebound only when it changes.
  VkDescriptorSet set = mesh && mesh->morphSet() ? mesh->morphSet() : morphPlaceholderSet_;
  if (set == rp.boundMorphSet) return;
  vkCmdBindDescriptorSets(rp.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, kMorphSet, 1, &set, 0, nullptr);
  rp.boundMorphSet = set;
}

void SceneRenderer::pushMesh(RecordPass& rp, const MeshDraw& d, size_t i, uint32_t flags, const glm::vec4& color,
                             float pull, const glm::vec4* baseLinear) {
  MeshPush p{};
  p.model = d.model;
  p.color = color;
  p.baseLinear = baseLinear ? *baseLinear : linearRgb(color);
  p.jointOffset = rp.jointBase + drawJointOffsets_[i];
  p.jointCount = d.jointMatrices.empty() ? 1u : static_cast<uint32_t>(d.jointMatrices.size());
  p.flags = flags;
  p.depthPull = pull;
  setMorph(rp, p, d.mesh, i);
  vkCmdPushConstants(rp.cmd, layout_, kPushStages, 0, sizeof(p), &p);
}

// One draw per material part: its factor (linear) as the base colour, its texture and the vertex
// colours multiplied in; parts without a material colour keep the draw's colour. Set 3 (the
// part's base colour texture, or the white placeholder) is rebound only when it changes.
void SceneRenderer::drawParts(RecordPass& rp, const MeshDraw& d, size_t i, uint32_t flags, const glm::vec4& color) {
  for (const GpuMeshPart& part : d.mesh->parts()) {
    if (part.indexCount == 0) continue;
    uint32_t f = flags;
    glm::vec4 base = linearRgb(color);
    VkDescriptorSet set = whiteTexture_->set();
    if (d.materials && part.coloured) {
      base = glm::vec4(glm::vec3(part.factor), color.a);
      if (part.texture) f |= kDrawTextured, set = part.texture;
      if (d.mesh->hasVertexColors()) f |= kDrawVertexColor;
    }
    pushMesh(rp, d, i, f, color, 0.0f, &base);
    if (set != rp.boundMaterialSet) {
      vkCmdBindDescriptorSets(rp.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, kMaterialSet, 1, &set, 0, nullptr);
      rp.boundMaterialSet = set;
    }
    vkCmdDrawIndexed(rp.cmd, part.indexCount, 1, part.firstIndex, 0, 0);
  }
}

void SceneRenderer::drawGenerated(RecordPass& rp, const GeneratedMeshDraw& g, VkPipeline pipeline,
                                  const glm::vec4& color, uint32_t flags, float pull) {
  if (!g.positions || !g.normals || !g.indices || !g.indirect || !(g.opacity > 0.0f)) return;
  VkCommandBuffer cmd = rp.cmd;
  bindPipeline(rp, pipeline);
  MeshPush p{};
  p.model = g.model;
  p.color = color;
  p.baseLinear = linearRgb(p.color);
  p.jointCount = 1;
  p.flags = flags | (g.selected ? kDrawSelected : 0u);
  p.depthPull = pull;
  vkCmdPushConstants(cmd, layout_, kPushStages, 0, sizeof(p), &p);
  VkBuffer streams[2] = {g.positions, g.normals};
  VkDeviceSize offsets[2] = {0, 0};
  vkCmdBindVertexBuffers(cmd, 0, 2, streams, offsets);
  vkCmdBindIndexBuffer(cmd, g.indices, 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexedIndirect(cmd, g.indirect, g.indirectOffset, 1, sizeof(VkDrawIndexedIndirectCommand));
}

void SceneRenderer::drawTransitions(const Scene& scene, RecordPass& rp) {
  // Set 0 stays bound (the layouts agree on it); set 1 per draw at its record's offset.
  Slot& slot = *rp.slot;
  transitionParamOffsets_.assign(scene.transitionMeshes.size(), UINT32_MAX);
  for (size_t k = 0; k < scene.transitionMeshes.size(); ++k) {
    const TransitionMeshDraw& t = scene.transitionMeshes[k];
    const MeshDraw& d = t.draw;
    if (!d.mesh || !t.binding || !t.frame || d.mesh->indexCount() == 0 || !(d.opacity > 0.0f)) continue;
    if (size_t(t.firstVertex) + d.mesh->vertexCount() > t.binding->vertexCount()) continue;
    const uint32_t paramOffset = static_cast<uint32_t>(slot.transitionParamsUsed);
    transitionParamOffsets_[k] = paramOffset;
    packTransitionParams(*t.frame, *reinterpret_cast<TransitionParams*>(
                                       static_cast<uint8_t*>(slot.transitionParams.mapped) + paramOffset));
    slot.transitionParamsUsed += transitionParamStride_;
    if (t.binding->hasColors())  // the variant that fades into the stand-in's colours
      bindPipeline(rp, d.opacity < 1.0f ? transitionColorDitherPipeline_[d.doubleSided]
                                        : transitionColorPipeline_[d.doubleSided]);
    else
      bindPipeline(rp, d.opacity < 1.0f ? transitionDitherPipeline_[d.doubleSided] : transitionPipeline_[d.doubleSided]);
    vkCmdBindDescriptorSets(rp.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, transitionLayout_, 1, 1, &slot.transitionSet, 1,
                            &paramOffset);
    slot.transitionSetBound = true;
    d.mesh->bindTriangles(rp.cmd);
    t.binding->bind(rp.cmd, t.firstVertex);
    drawParts(rp, d, scene.meshes.size() + scene.weightOverlays.size() + k,
              (d.selected ? kDrawSelected : 0u) | fadeFlags(d), fadeColor(d));
  }
}

void SceneRenderer::drawParticlesAndWeights(const Scene& scene, RecordPass& rp) {
  VkCommandBuffer cmd = rp.cmd;
  Slot& slot = *rp.slot;
  // Particles: one instanced draw of a triangle per particle draw, at its place in the ring buffer.
  VkDeviceSize particleOffset = rp.particleBase;
  for (const ParticleSpheresDraw& d : scene.particles) {
    const VkDeviceSize bytes = d.spheres.size() * kParticleBytes;
    if (d.spheres.empty()) continue;
    bindPipeline(rp, particlePipeline_);
    MeshPush p{};
    p.model = glm::mat4(1.0f);
    p.color = d.color;
    p.baseLinear = linearRgb(d.color);
    p.jointCount = 1;
    p.flags = d.selected ? kDrawSelected : 0u;
    vkCmdPushConstants(cmd, layout_, kPushStages, 0, sizeof(p), &p);
    const VkBuffer buffers[2] = {slot.particles.buffer, slot.particles.buffer};
    const VkDeviceSize offsets[2] = {particleOffset, particleOffset + d.spheres.size() * sizeof(glm::vec4)};
    vkCmdBindVertexBuffers(cmd, 0, 2, buffers, offsets);
    vkCmdDraw(cmd, 3, static_cast<uint32_t>(d.spheres.size()), 0, 0);
    particleOffset += bytes;
  }
  for (size_t k = 0; k < scene.weightOverlays.size(); ++k) {
    const WeightOverlayDraw& d = scene.weightOverlays[k];
    if (!d.mesh || d.mesh->indexCount() == 0 || d.weights.size() != d.mesh->vertexCount()) continue;
    bindPipeline(rp, weightPipeline_);
    MeshPush p{};
    p.model = d.model;
    p.color = glm::vec4(1.0f);
    p.jointOffset = rp.jointBase + drawJointOffsets_[scene.meshes.size() + k];
    p.jointCount = d.jointMatrices.empty() ? 1u : static_cast<uint32_t>(d.jointMatrices.size());
    setMorph(rp, p, d.mesh, scene.meshes.size() + k);
    vkCmdPushConstants(cmd, layout_, kPushStages, 0, sizeof(p), &p);
    d.mesh->bindTriangles(cmd);
    const VkDeviceSize offset = rp.weightBase + rp.weightOffsets[k];
    vkCmdBindVertexBuffers(cmd, kVertexPaintWeight, 1, &slot.weights.buffer, &offset);
    vkCmdDrawIndexed(cmd, d.mesh->indexCount(), 1, 0, 0, 0);
  }
}

void SceneRenderer::drawSurfaces(const Scene& scene, RecordPass& rp) {
  // Set 3 starts as the white placeholder: the wireframe pass reads it too, also for meshes not drawn.
  rp.boundMaterialSet = whiteTexture_->set();
  vkCmdBindDescriptorSets(rp.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, kMaterialSet, 1, &rp.boundMaterialSet, 0,
                          nullptr);
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshDraw& d = scene.meshes[i];
    if (!d.mesh || d.mesh->indexCount() == 0 || !(d.opacity > 0.0f)) continue;
    bindPipeline(rp, d.opacity < 1.0f ? meshDitherPipeline_[d.doubleSided] : meshPipeline_[d.doubleSided]);
    d.mesh->bindTriangles(rp.cmd);
    drawParts(rp, d, i, (d.selected ? kDrawSelected : 0u) | fadeFlags(d), fadeColor(d));
  }
  drawTransitions(scene, rp);
  for (const GeneratedMeshDraw& g : scene.generatedMeshes)
    drawGenerated(rp, g, g.opacity < 1.0f ? generatedDitherPipeline_ : generatedPipeline_, fadeColor(g), fadeFlags(g),
                  0.0f);
  drawParticlesAndWeights(scene, rp);
}

void SceneRenderer::drawWireframes(const Scene& scene, RecordPass& rp) {
  const SceneOptions& opt = scene.options;
  VkCommandBuffer cmd = rp.cmd;
  auto wireColor = [&](bool selected) { return selected ? glm::mix(opt.wireColor, opt.selectColor, 0.6f) : opt.wireColor; };
  auto drawEdges = [&](const GpuMesh& mesh) {
    if (edgeListWireframe_) {
      if (mesh.edgeIndexCount() == 0) return;  // uploaded without an edge list
      mesh.bindEdges(cmd);
      vkCmdDrawIndexed(cmd, mesh.edgeIndexCount(), 1, 0, 0, 0);
    } else if (mesh.indexCount() > 0) {
      mesh.bindTriangles(cmd);
      vkCmdDrawIndexed(cmd, mesh.indexCount(), 1, 0, 0, 0);
    }
  };
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshDraw& d = scene.meshes[i];
    if (!d.mesh) continue;
    bindPipeline(rp, wirePipeline_[d.doubleSided]);
    pushMesh(rp, d, i, kDrawWireframe | (d.selected ? kDrawSelected : 0u), wireColor(d.selected), kWireDepthPull);
    drawEdges(*d.mesh);
  }
  // The transitions' edges where their vertex shader puts them (drawn above: their set 1 record is written).
  for (size_t k = 0; k < scene.transitionMeshes.size(); ++k) {
    const TransitionMeshDraw& t = scene.transitionMeshes[k];
    if (transitionParamOffsets_[k] == UINT32_MAX) continue;
    const MeshDraw& d = t.draw;
    bindPipeline(rp, transitionWirePipeline_[d.doubleSided]);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, transitionLayout_, 1, 1, &rp.slot->transitionSet, 1,
                            &transitionParamOffsets_[k]);
    pushMesh(rp, d, scene.meshes.size() + scene.weightOverlays.size() + k,
             kDrawWireframe | (d.selected ? kDrawSelected : 0u), wireColor(d.selected), kWireDepthPull);
    t.binding->bind(cmd, t.firstVertex);
    drawEdges(*d.mesh);
  }
  // Generated meshes (the GPU polygoniser's) have no edge list: polygon-mode lines only.
  if (generatedWirePipeline_)
    for (const GeneratedMeshDraw& g : scene.generatedMeshes)
      drawGenerated(rp, g, generatedWirePipeline_, wireColor(g.selected), kDrawWireframe, kWireDepthPull);
}

void SceneRenderer::drawLinesAndAxes(const ViewportRect& rect, const SceneOptions& opt, RecordPass& rp) {
  VkCommandBuffer cmd = rp.cmd;
  auto drawLines = [&](VkPipeline pipeline, const glm::mat4& matrix, uint32_t first, uint32_t count) {
    if (count == 0) return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdPushConstants(cmd, layout_, kPushStages, 0, sizeof(glm::mat4), &matrix);
    vkCmdBindVertexBuffers(cmd, 0, 1, &rp.slot->lines.buffer, &rp.lineOffset);
    vkCmdDraw(cmd, count, 1, first, 0);
  };
  drawLines(linePipeline_, rp.viewProj, 0, rp.depthLineCount);
  if (opt.grid) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, gridPipeline_);
    vkCmdDraw(cmd, 6, 2 * (2 * rp.gridLines + 1), 0, 0);  // one quad per line (grid.vert)
  }
  drawLines(overlayPipeline_, rp.viewProj, rp.depthLineCount, rp.overlayLineCount);

  const uint32_t size = opt.axisIndicatorPx, margin = 6;
  if (opt.axisIndicator && rect.width >= size + 2 * margin && rect.height >= size + 2 * margin) {
    VkViewport corner{float(rect.x + margin), float(rect.y + int32_t(rect.height - size - margin)), float(size),
                      float(size), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &corner);
    // Camera rotation only, orthographic, y flipped for Vulkan.
    glm::mat4 ortho = glm::orthoRH_ZO(-1.3f, 1.3f, -1.3f, 1.3f, -2.0f, 2.0f);
    ortho[1][1] = -ortho[1][1];
    drawLines(overlayPipeline_, ortho * glm::mat4(glm::mat3(rp.view)), rp.axisFirst, 6);
    vkCmdSetViewport(cmd, 0, 1, &rp.viewport);
  }
}

Status SceneRenderer::record(VkCommandBuffer cmd, uint64_t frameSerial, const ViewportRect& rect,
                             const OrbitCamera& camera, const Scene& scene) {
  if (rect.width == 0 || rect.height == 0) return Status::success();
  Slot& slot = *slots_[frameSerial % kFramesInFlight];
  if (slot.serial != frameSerial) rewind(slot, frameSerial);  // the GPU is done with that slot's last frame
  RecordPass rp;
  rp.cmd = cmd;
  rp.slot = &slot;
  gatherFrameData(scene, rp);
  if (Status s = uploadFrameData(scene, rp); !s) return s;
  writeFrameUniforms(rect, camera, scene.options, rp);
  beginViewport(rect, scene.options, rp);
  drawSurfaces(scene, rp);
  if (scene.options.wireframe) drawWireframes(scene, rp);
  drawLinesAndAxes(rect, scene.options, rp);
  return Status::success();
}

}  // namespace animorph::gpu
