#pragma once
// A Mesh (rig/character.h) uploaded once to device memory: positions, normals,
// two sets of 4 joint indices (u16) and weights, triangle indices, and, when
// the device cannot draw polygons as lines, an edge list for the wireframe.
// A mesh with blend shapes also gets its morph deltas as a storage buffer in a
// descriptor set of its own (set AM_MORPH_SET of the skinned vertex shaders).
// Material streams: texture coordinates and COLOR_0 (bindings AM_VERTEX_TEXCOORD0 /
// AM_VERTEX_COLOR0), and the triangles of each material (parts()).
#include <memory>
#include <span>
#include <vector>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "core/math/bounds.h"
#include "core/rig/character.h"

namespace animorph::gpu {

// The triangles [firstIndex, firstIndex + indexCount) of a GpuMesh drawn with one material.
struct GpuMeshPart {
  uint32_t firstIndex = 0, indexCount = 0;
  int material = -1;                         // index into the character's materials, or -1
  glm::vec4 factor{1.0f};                    // the material's base colour factor (linear)
  VkDescriptorSet texture = VK_NULL_HANDLE;  // set AM_MATERIAL_SET of its base colour texture; null: none
  // The material gives the part a colour (a factor other than white, a texture, or vertex
  // colours other than white); otherwise it is drawn in the draw's colour (the viewport grey).
  bool coloured = false;
};

class GpuMesh {
 public:
  // Uploads mesh (waits for the copy). Missing normals are computed (area-weighted);
  // a mesh without joints binds every vertex to joint 0. The edge list is built when
  // the device lacks fillModeNonSolid or withEdgeList is set. Errors name the mesh
  // and the problem: no vertices, an index out of range, attribute arrays of the
  // wrong length, more than 65535 joints, morph targets whose deltas do not
  // have one entry per vertex, Vulkan failures.
  static Result<std::unique_ptr<GpuMesh>> upload(Context& ctx, const Mesh& mesh, bool withEdgeList = false);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;

  // Binds the vertex streams (bindings AM_VERTEX_*) and the triangle index buffer.
  void bindTriangles(VkCommandBuffer cmd) const;
  // Binds the vertex streams and the edge index buffer (edgeIndexCount() > 0 only).
  void bindEdges(VkCommandBuffer cmd) const;

  uint32_t vertexCount() const { return vertexCount_; }
  // The material parts (mesh.parts whose ranges lie inside the indices; else one part, the
  // whole mesh with mesh.material), factors white and no textures until setMaterials.
  std::span<const GpuMeshPart> parts() const { return parts_; }
  // Vertex colours other than white: multiplied in (AM_DRAW_VERTEX_COLOR).
  bool hasVertexColors() const { return hasVertexColors_; }
  // Gives every part its material's factor and texture set: textureSets[i] is the set of
  // materials' texture i (null: none or not uploaded). Materials out of range stay white.
  void setMaterials(std::span<const Material> materials, std::span<const VkDescriptorSet> textureSets);
  // Morph targets on the device: the mesh's, or the first ones whose deltas fit
  // the device's maxStorageBufferRange (the rest are not drawn by the GPU).
  uint32_t morphTargetCount() const { return morphTargetCount_; }
  // The descriptor set of the deltas (layout: createMorphSetLayout); null without targets.
  VkDescriptorSet morphSet() const { return morphSet_; }
  uint32_t indexCount() const { return indexCount_; }
  uint32_t edgeIndexCount() const { return edgeIndexCount_; }  // 2 per unique edge; 0 when not built
  const Bounds& bounds() const { return bounds_; }             // of the bind-pose positions
  const std::string& name() const { return name_; }
  // Distinct for every upload and every setMaterials of any GpuMesh in the process: two draws of
  // meshes with the same serial draw the same (the kept viewport image's test, scene_fingerprint.h).
  uint64_t contentSerial() const { return contentSerial_; }

 private:
  explicit GpuMesh(VkDevice device) : device_(device), contentSerial_(nextContentSerial()) {}
  static uint64_t nextContentSerial();
  VkDevice device_;
  uint64_t contentSerial_ = 0;
  Buffer buffer_;  // every stream and both index lists, at the offsets below
  static constexpr int kStreams = 8;  // AM_VERTEX_POSITION..WEIGHTS1, then TEXCOORD0, COLOR0
  VkDeviceSize streamOffsets_[kStreams]{};
  std::vector<GpuMeshPart> parts_;
  bool hasVertexColors_ = false;
  VkDeviceSize indexOffset_ = 0, edgeOffset_ = 0;
  uint32_t vertexCount_ = 0, indexCount_ = 0, edgeIndexCount_ = 0;
  Bounds bounds_;
  std::string name_;
  Buffer morphBuffer_;  // AM_MORPH_DELTA_FLOATS floats per target and vertex
  VkDescriptorSetLayout morphLayout_ = VK_NULL_HANDLE;
  VkDescriptorPool morphPool_ = VK_NULL_HANDLE;
  VkDescriptorSet morphSet_ = VK_NULL_HANDLE;
  uint32_t morphTargetCount_ = 0;
  Status uploadMorphTargets(Context& ctx, const Mesh& mesh);
  void bindStreams(VkCommandBuffer cmd) const;
};

// The layout of set AM_MORPH_SET (one storage buffer, vertex stage): the
// renderer's pipeline layouts and every GpuMesh's set use identical ones.
Result<VkDescriptorSetLayout> createMorphSetLayout(VkDevice device);

}  // namespace animorph::gpu
