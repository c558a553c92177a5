#pragma once
// Draws the 3D scene of a viewport: skinned meshes (LBS in the vertex shader),
// optional wireframe overlay, ground grid, line overlays (skeleton) and an axis
// indicator, into a rectangle of any colour+depth target made by
// createSceneRenderPass (swapchain or offscreen). Per-frame data lives in
// host-visible ring buffers, one slot per frame in flight; steady-state frames
// allocate no Vulkan objects.
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/vulkan/context.h"
#include "gpu/render/gpu_mesh.h"
#include "gpu/render/gpu_texture.h"
#include "gpu/transition/gpu_standin_binding.h"
#include "gpu/render/line_batch.h"
#include "core/camera/camera.h"

namespace animorph {
struct TransitionFrame;
}

namespace animorph::gpu {

// Push constants of the mesh pipelines (defined in scene_renderer.cpp, mirrored by the shaders).
struct MeshPush;

// Pixel rectangle of the target to draw into (origin top-left); must lie within
// the render area (an empty rectangle draws nothing).
struct ViewportRect {
  int32_t x = 0, y = 0;
  uint32_t width = 0, height = 0;
};

struct MeshDraw {
  const GpuMesh* mesh = nullptr;
  glm::mat4 model{1.0f};                     // mesh node's world matrix
  std::span<const glm::mat4> jointMatrices;  // jointMatrices() of the node; empty: one identity
  // Blend-shape weights, one per morph target of the mesh (rig/pose.h
  // morphWeightsAt); empty or all zero: the bind shape. Copied while recording.
  std::span<const float> morphWeights;
  glm::vec4 color{0.62f, 0.62f, 0.62f, 1.0f};  // base colour (sRGB) of parts without a material colour
  // Draw the mesh's materials (GpuMesh::parts: factor x texture x vertex colour) where they give
  // a colour; false: every part in `color` (a BlobTree surface polygonised into a mesh).
  bool materials = true;
  bool selected = false;
  // glTF material.doubleSided: also draw back faces. Single-sided meshes cull
  // them (counter-clockwise is front, as in glTF), which also halves the
  // rasterisation work on CPU renderers.
  bool doubleSided = false;
  // Cross-fade (screen-door transparency, mesh_dither.frag): below 1 the mesh
  // covers this fraction of its pixels in a 4x4 Bayer pattern;
  // complementDither takes the complementary pattern, so two draws at
  // opacities o and 1 - o share the pixels without sorting.
  float opacity = 1.0f;
  bool complementDither = false;
};

// A skinned mesh collapsing onto / expanding from its stand-in, deformed in
// transition.vert (shaders/include/transition.glsl): the mesh and its pose as
// in MeshDraw, the vertices' stand-in binding (uploaded once per prepared
// morph) and the frame's parameters (a few KiB per draw, written to a ring
// buffer): no CPU transition and no mesh upload per frame.
struct TransitionMeshDraw {
  MeshDraw draw;
  const GpuStandinBinding* binding = nullptr;
  uint32_t firstVertex = 0;                // this mesh's first vertex in the binding
  const TransitionFrame* frame = nullptr;  // must stay valid until record() returns
};

// A non-skinned mesh that lives only in device buffers (made by GpuPolygonizer),
// drawn with vkCmdDrawIndexedIndirect: no CPU read-back. Buffers must stay
// valid until the frame that draws them completes.
struct GeneratedMeshDraw {
  // Positions and normals: a vec4 per vertex (xyz; a normal's w: the colour pass's colour).
  static constexpr uint32_t kVertexStride = 16;
  VkBuffer positions = VK_NULL_HANDLE;  // float xyz(w) per vertex, kVertexStride apart
  VkBuffer normals = VK_NULL_HANDLE;    // float xyz(w) per vertex (unit, outward), kVertexStride apart
  VkBuffer indices = VK_NULL_HANDLE;    // uint32 triangle list, counter-clockwise from outside
  VkBuffer indirect = VK_NULL_HANDLE;   // one VkDrawIndexedIndirectCommand at indirectOffset
  VkDeviceSize indirectOffset = 0;
  glm::mat4 model{1.0f};
  glm::vec4 color{0.62f, 0.62f, 0.62f, 1.0f};
  bool selected = false;
  float opacity = 1.0f;           // < 1: dithered cross-fade, as MeshDraw::opacity
  bool complementDither = false;
};

// A skinned mesh drawn as its weight map in heat colours (0 blue .. 1 red)
// instead of shaded (weight_overlay shaders). weights has one entry per
// vertex of mesh (a draw with another count is skipped); it is copied while
// recording, so it only has to live until record() returns.
struct WeightOverlayDraw {
  const GpuMesh* mesh = nullptr;
  glm::mat4 model{1.0f};
  std::span<const glm::mat4> jointMatrices;
  std::span<const float> weights;
  std::span<const float> morphWeights;  // as MeshDraw::morphWeights
};

// Particles drawn as spheres (the particle view while scrubbing, editor/particle_view.h): each a
// ray-cast impostor (particle_sphere shaders: an eye-facing triangle per instance) with the depth of
// its true surface, shaded like a mesh of its colour. spheres: world centre (xyz) and radius (w) of
// each; colors: each one's colour (RGBA8, sRGB; alpha 0, or colors empty: the draw's color);
// copied into the frame's ring buffer while recording (20 bytes a particle).
struct ParticleSpheresDraw {
  std::vector<glm::vec4> spheres;
  std::vector<uint32_t> colors;                  // empty or one per sphere: packed as LineVertex::rgba
  glm::vec4 color{0.55f, 0.68f, 0.82f, 1.0f};  // sRGB
  bool selected = false;
};

struct SceneOptions {
  glm::vec4 background{0.23f, 0.24f, 0.26f, 1.0f};  // the viewport rectangle is cleared to this
  bool grid = true;
  float gridCellM = 1.0f;            // minor line spacing; a major line every 10 cells
  bool wireframe = false;            // draw mesh edges over the shaded surface (meshes, transitions, generated meshes)
  glm::vec4 wireColor{0.05f, 0.05f, 0.05f, 1.0f};
  glm::vec4 selectColor{1.0f, 0.62f, 0.15f, 1.0f};
  bool axisIndicator = true;         // X/Y/Z tripod in the lower-left corner
  uint32_t axisIndicatorPx = 72;     // its square size in pixels
};

struct Scene {
  std::vector<MeshDraw> meshes;
  std::vector<GeneratedMeshDraw> generatedMeshes;  // GPU-polygonised previews
  std::vector<TransitionMeshDraw> transitionMeshes;  // collapse / expansion (vertex-shader transition)
  std::vector<WeightOverlayDraw> weightOverlays;   // weight painting
  std::vector<ParticleSpheresDraw> particles;      // the particle view
  LineBatch lines;    // depth-tested lines (guides, bounds)
  LineBatch overlay;  // drawn on top of everything (skeleton overlay)
  SceneOptions options;
};

struct SceneRendererSettings {
  // Draw wireframes from per-mesh edge lists even when fillModeNonSolid exists
  // (the path devices without it take; meshes need GpuMesh::upload(..., true)).
  bool forceEdgeListWireframe = false;
};

class SceneRenderer {
 public:
  // Pipelines for renderPass (from createSceneRenderPass with the context's depth
  // format) and kFramesInFlight ring-buffer slots. Errors: Vulkan failures.
  static Result<std::unique_ptr<SceneRenderer>> create(Context& ctx, VkRenderPass renderPass,
                                                        SceneRendererSettings settings = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Records scene, seen through camera, into rect of the render pass instance
  // active on cmd (sets viewport and scissor; the rectangle is cleared first).
  // frameSerial numbers the frame being recorded (Frame::serial of the
  // swapchain, OffscreenTarget::serial()); its ring-buffer slot is
  // frameSerial % kFramesInFlight, and the caller guarantees the GPU is done
  // with the frame kFramesInFlight before (Swapchain and OffscreenTarget do).
  // Several calls in one frame (several viewports) append to the slot.
  // Errors: a ring buffer could not grow.
  Status record(VkCommandBuffer cmd, uint64_t frameSerial, const ViewportRect& rect, const OrbitCamera& camera,
                const Scene& scene);

  bool wireframeUsesEdgeLists() const { return edgeListWireframe_; }

 private:
  struct Slot;
  explicit SceneRenderer(Context& ctx);
  Status init(VkRenderPass renderPass, SceneRendererSettings settings);
  // init's steps, in order; each returns what failed to be made.
  Status createLayouts();
  Status createDescriptorPool();
  Status createPipelines(VkRenderPass renderPass);
  Status reserve(Slot& slot, VkDeviceSize jointBytes, VkDeviceSize lineBytes, VkDeviceSize weightBytes = 0,
                 VkDeviceSize particleBytes = 0);
  Status reserveTransitionParams(Slot& slot, VkDeviceSize bytes);
  void rewind(Slot& slot, uint64_t frameSerial);

  // record()'s steps, in order; rp carries one call's state (scene_renderer.cpp).
  struct RecordPass;
  // Joint matrices, morph weights, paint weights and line vertices of the scene into the scratch arrays.
  void gatherFrameData(const Scene& scene, RecordPass& rp);
  // The scratch arrays and the particles into the slot's buffers (grown as needed); fails when a
  // buffer cannot grow.
  Status uploadFrameData(const Scene& scene, RecordPass& rp);
  // The camera, light and grid into this call's frame uniforms.
  void writeFrameUniforms(const ViewportRect& rect, const OrbitCamera& camera, const SceneOptions& opt, RecordPass& rp);
  // Viewport, scissor, clear, and set 0 bound.
  void beginViewport(const ViewportRect& rect, const SceneOptions& opt, RecordPass& rp);
  // Meshes, transitions, generated meshes, particles and weight overlays.
  void drawSurfaces(const Scene& scene, RecordPass& rp);
  void drawTransitions(const Scene& scene, RecordPass& rp);
  void drawParticlesAndWeights(const Scene& scene, RecordPass& rp);
  // The wireframe pass over meshes, transitions and generated meshes.
  void drawWireframes(const Scene& scene, RecordPass& rp);
  // Depth-tested lines, the grid, overlay lines and the corner axis tripod.
  void drawLinesAndAxes(const ViewportRect& rect, const SceneOptions& opt, RecordPass& rp);
  // Binds the pipeline unless bound; a draw's push constants (joints, morphs: draw index i); a
  // generated (indirect) mesh's draw.
  void bindPipeline(RecordPass& rp, VkPipeline p);
  void setMorph(RecordPass& rp, MeshPush& p, const GpuMesh* mesh, size_t i);
  // baseLinear: the base colour in linear light; null: color's.
  void pushMesh(RecordPass& rp, const MeshDraw& d, size_t i, uint32_t flags, const glm::vec4& color, float pull,
                const glm::vec4* baseLinear = nullptr);
  // A mesh's material parts, each in its factor, texture and vertex colours (MeshDraw::materials).
  void drawParts(RecordPass& rp, const MeshDraw& d, size_t i, uint32_t flags, const glm::vec4& color);
  void drawGenerated(RecordPass& rp, const GeneratedMeshDraw& g, VkPipeline pipeline, const glm::vec4& color,
                     uint32_t flags, float pull);

  Context& ctx_;
  bool edgeListWireframe_ = false;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout morphSetLayout_ = VK_NULL_HANDLE;  // set AM_MORPH_SET (render/gpu_mesh.h)
  Buffer morphPlaceholder_;                                // bound for meshes without morph targets
  VkDescriptorSet morphPlaceholderSet_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout materialSetLayout_ = VK_NULL_HANDLE;  // set AM_MATERIAL_SET (render/gpu_texture.h)
  std::unique_ptr<GpuTexture> whiteTexture_;                   // 1x1 white: bound for parts without a texture
  VkPipeline meshPipeline_[2]{};  // [doubleSided]
  VkPipeline wirePipeline_[2]{};  // [doubleSided]
  VkPipeline generatedPipeline_ = VK_NULL_HANDLE;  // GeneratedMeshDraw: positions + normals, indirect
  VkPipeline meshDitherPipeline_[2]{};             // [doubleSided], MeshDraw::opacity < 1
  VkPipeline generatedDitherPipeline_ = VK_NULL_HANDLE;  // GeneratedMeshDraw::opacity < 1
  VkDescriptorSetLayout transitionSetLayout_ = VK_NULL_HANDLE;  // set 1: TransitionParams (dynamic offset)
  VkPipelineLayout transitionLayout_ = VK_NULL_HANDLE;
  VkPipeline transitionPipeline_[2]{};             // [doubleSided]
  VkPipeline transitionDitherPipeline_[2]{};       // [doubleSided]
  VkPipeline transitionColorPipeline_[2]{};        // [doubleSided]: bindings with stand-in colours (AM_SPEC_STANDIN_COLOR)
  VkPipeline transitionColorDitherPipeline_[2]{};  // [doubleSided]: the same, dithered
  VkPipeline transitionWirePipeline_[2]{};         // [doubleSided]: the wireframe pass over transitions
  VkPipeline generatedWirePipeline_ = VK_NULL_HANDLE;  // null on the edge-list path (generated meshes have no edge list)
  std::vector<uint32_t> transitionParamOffsets_;   // per transition draw of the current record (the wireframe pass rebinds)
  VkDeviceSize transitionParamStride_ = 0;         // sizeof(TransitionParams), storage-offset aligned
  VkPipeline weightPipeline_ = VK_NULL_HANDLE;     // WeightOverlayDraw: mesh streams + a weight stream
  VkPipeline particlePipeline_ = VK_NULL_HANDLE;   // ParticleSpheresDraw: instanced impostors
  VkPipeline gridPipeline_ = VK_NULL_HANDLE;
  VkPipeline linePipeline_ = VK_NULL_HANDLE;     // depth-tested
  VkPipeline overlayPipeline_ = VK_NULL_HANDLE;  // always on top
  std::vector<std::unique_ptr<Slot>> slots_;
  VkDeviceSize uniformStride_ = 256;  // sizeof(FrameUniforms) rounded to the device's UBO offset alignment
  std::vector<glm::mat4> jointScratch_;
  std::vector<LineVertex> lineScratch_;
  std::vector<uint32_t> drawJointOffsets_;  // per mesh draw, then per weight overlay
  struct DrawMorph {
    uint32_t offset = 0;  // float index of the (target, weight) pairs in this call's joint data
    uint32_t count = 0;   // active targets; 0: none
  };
  std::vector<DrawMorph> drawMorphs_;  // indexed as drawJointOffsets_
  Status initMorphPlaceholder();
  void addMorphWeights(const GpuMesh* mesh, std::span<const float> weights);
  std::vector<float> weightScratch_;
};

}  // namespace animorph::gpu
