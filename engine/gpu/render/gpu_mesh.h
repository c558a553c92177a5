#pragma once
// A Mesh (rig/character.h) uploaded once to device memory: positions, normals,
// two sets of 4 joint indices (u16) and weights, triangle indices, and, when
// the device cannot draw polygons as lines, an edge list for the wireframe.
#include <memory>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "core/math/bounds.h"
#include "core/rig/character.h"

namespace animorph::gpu {

class GpuMesh {
 public:
  // Uploads mesh (waits for the copy). Missing normals are computed (area-weighted);
  // a mesh without joints binds every vertex to joint 0. The edge list is built when
  // the device lacks fillModeNonSolid or withEdgeList is set. Errors name the mesh
  // and the problem: no vertices, an index out of range, attribute arrays of the
  // wrong length, more than 65535 joints, Vulkan failures.
  static Result<std::unique_ptr<GpuMesh>> upload(Context& ctx, const Mesh& mesh, bool withEdgeList = false);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;

  // Binds the vertex streams (bindings AM_VERTEX_*) and the triangle index buffer.
  void bindTriangles(VkCommandBuffer cmd) const;
  // Binds the vertex streams and the edge index buffer (edgeIndexCount() > 0 only).
  void bindEdges(VkCommandBuffer cmd) const;

  uint32_t vertexCount() const { return vertexCount_; }
  uint32_t indexCount() const { return indexCount_; }
  uint32_t edgeIndexCount() const { return edgeIndexCount_; }  // 2 per unique edge; 0 when not built
  const Bounds& bounds() const { return bounds_; }             // of the bind-pose positions
  const std::string& name() const { return name_; }

 private:
  explicit GpuMesh(VkDevice device) : device_(device) {}
  VkDevice device_;
  Buffer buffer_;  // every stream and both index lists, at the offsets below
  VkDeviceSize streamOffsets_[6]{};
  VkDeviceSize indexOffset_ = 0, edgeOffset_ = 0;
  uint32_t vertexCount_ = 0, indexCount_ = 0, edgeIndexCount_ = 0;
  Bounds bounds_;
  std::string name_;
};

}  // namespace animorph::gpu
