#include "gpu/render/gpu_mesh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <vector>

#include "core/rig/mesh_normals.h"
#include "core/rig/morph_targets.h"
#include "shared_constants.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

namespace {

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

std::vector<uint32_t> uniqueEdges(const std::vector<uint32_t>& tris) {
  std::vector<uint64_t> keys;
  keys.reserve(tris.size());
  for (size_t t = 0; t + 2 < tris.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      uint32_t a = tris[t + e], b = tris[t + (e + 1) % 3];
      if (a > b) std::swap(a, b);
      keys.push_back((uint64_t(a) << 32) | b);
    }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<uint32_t> out;
  out.reserve(keys.size() * 2);
  for (uint64_t k : keys) {
    out.push_back(uint32_t(k >> 32));
    out.push_back(uint32_t(k & 0xffffffffu));
  }
  return out;
}

}  // namespace

Result<std::unique_ptr<GpuMesh>> GpuMesh::upload(Context& ctx, const Mesh& mesh, bool withEdgeList) {
  const std::string what = "mesh '" + mesh.name + "'";
  const size_t n = mesh.positions.size();
  if (n == 0) return Error{what + ": no vertices"};
  if (n > 0xffffffffu) return Error{what + ": too many vertices"};
  if (mesh.indices.size() % 3 != 0) return Error{what + ": index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3"};
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= n)
      return Error{what + ": index " + std::to_string(i) + " = " + std::to_string(mesh.indices[i]) +
                   " is out of range (" + std::to_string(n) + " vertices)"};
  if (!mesh.normals.empty() && mesh.normals.size() != n) return Error{what + ": " + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) + " vertices"};
  if (!mesh.joints0.empty() && (mesh.joints0.size() != n || mesh.weights0.size() != n))
    return Error{what + ": JOINTS_0/WEIGHTS_0 do not have one entry per vertex"};
  if (!mesh.joints1.empty() && (mesh.joints1.size() != n || mesh.weights1.size() != n))
    return Error{what + ": JOINTS_1/WEIGHTS_1 do not have one entry per vertex"};

  std::vector<glm::vec3> computed;
  const std::vector<glm::vec3>* normals = &mesh.normals;
  if (mesh.normals.empty()) {
    computed = computeAreaWeightedNormals(mesh.positions, mesh.indices);
    normals = &computed;
  }
  // Joint indices as u16; an index that does not fit becomes 0xffff, which the
  // shader ignores like any index beyond the draw's joint count (as the CPU does).
  auto packJoints = [](const glm::uvec4& j) {
    std::array<uint16_t, 4> out{};
    for (int k = 0; k < 4; ++k) out[k] = static_cast<uint16_t>(std::min<uint32_t>(j[k], 0xffffu));
    return out;
  };
  std::vector<std::array<uint16_t, 4>> j0(n), j1(n);
  std::vector<glm::vec4> w0(n, glm::vec4(1, 0, 0, 0)), w1(n, glm::vec4(0.0f));
  if (!mesh.joints0.empty()) {
    for (size_t v = 0; v < n; ++v) j0[v] = packJoints(mesh.joints0[v]);
    w0 = mesh.weights0;
  }
  if (!mesh.joints1.empty()) {
    for (size_t v = 0; v < n; ++v) j1[v] = packJoints(mesh.joints1[v]);
    w1 = mesh.weights1;
  }
  if (!mesh.texcoords0.empty() && mesh.texcoords0.size() != n) return Error{what + ": texture coordinates do not have one entry per vertex"};
  if (!mesh.colors.empty() && mesh.colors.size() != n) return Error{what + ": COLOR_0 does not have one entry per vertex"};
  std::vector<glm::vec2> uv = mesh.texcoords0.empty() ? std::vector<glm::vec2>(n, glm::vec2(0.0f)) : mesh.texcoords0;
  std::vector<glm::vec4> col = mesh.colors.empty() ? std::vector<glm::vec4>(n, glm::vec4(1.0f)) : mesh.colors;
  std::vector<uint32_t> edges;
  if (withEdgeList || !ctx.supportsWireframeFill()) edges = uniqueEdges(mesh.indices);

  std::unique_ptr<GpuMesh> gm(new GpuMesh(ctx.device()));
  const void* streams[kStreams] = {mesh.positions.data(), normals->data(), j0.data(), j1.data(), w0.data(), w1.data(),
                                   uv.data(), col.data()};
  const VkDeviceSize strides[kStreams] = {12, 12, 8, 8, 16, 16, 8, 16};
  VkDeviceSize size = 0;
  for (int s = 0; s < kStreams; ++s) {
    gm->streamOffsets_[s] = size;
    size = alignUp(size + strides[s] * n, 16);
  }
  gm->indexOffset_ = size;
  size = alignUp(size + 4 * mesh.indices.size(), 16);
  gm->edgeOffset_ = size;
  size += 4 * edges.size();
  std::vector<uint8_t> blob(size);
  for (int s = 0; s < kStreams; ++s) std::memcpy(blob.data() + gm->streamOffsets_[s], streams[s], strides[s] * n);
  if (!mesh.indices.empty()) std::memcpy(blob.data() + gm->indexOffset_, mesh.indices.data(), 4 * mesh.indices.size());
  if (!edges.empty()) std::memcpy(blob.data() + gm->edgeOffset_, edges.data(), 4 * edges.size());

  Result<Buffer> buf = createDeviceBuffer(ctx, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                          blob.data(), size);
  if (!buf) return Error{what + ": " + buf.error()};
  gm->buffer_ = *buf;
  gm->vertexCount_ = static_cast<uint32_t>(n);
  gm->indexCount_ = static_cast<uint32_t>(mesh.indices.size());
  gm->edgeIndexCount_ = static_cast<uint32_t>(edges.size());
  gm->bounds_ = mesh.bounds();
  gm->name_ = mesh.name;
  gm->hasVertexColors_ = std::any_of(col.begin(), col.end(), [](const glm::vec4& c) {
    return c.r < 0.999f || c.g < 0.999f || c.b < 0.999f;
  });
  for (const Mesh::Part& p : mesh.parts)
    if (p.indexCount > 0 && p.firstIndex <= mesh.indices.size() && p.indexCount <= mesh.indices.size() - p.firstIndex)
      gm->parts_.push_back({p.firstIndex, p.indexCount, p.material});
  if (gm->parts_.empty()) gm->parts_.push_back({0, gm->indexCount_, mesh.material});
  gm->setMaterials({}, {});
  if (!mesh.morphTargets.empty())
    if (Status st = gm->uploadMorphTargets(ctx, mesh); !st) return Error{what + ": " + st.error()};
  return gm;
}

Result<VkDescriptorSetLayout> createMorphSetLayout(VkDevice device) {
  VkDescriptorSetLayoutBinding b{AM_MORPH_BINDING_DELTAS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                                 VK_SHADER_STAGE_VERTEX_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = 1;
  ci.pBindings = &b;
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  AM_VK_TRY(vkCreateDescriptorSetLayout(device, &ci, nullptr, &layout), "vkCreateDescriptorSetLayout");
  return layout;
}

// Deltas target-major (target t, vertex v at (t * n + v) * 6 floats: position, normal),
// as many targets as one storage-buffer descriptor can address.
Status GpuMesh::uploadMorphTargets(Context& ctx, const Mesh& mesh) {
  if (std::string bad = checkMorphTargets(mesh); !bad.empty()) return Error{bad};
  const size_t n = mesh.positions.size();
  const VkDeviceSize perTarget = VkDeviceSize(n) * kMorphDeltaFloats * sizeof(float);
  const VkDeviceSize range = ctx.properties().limits.maxStorageBufferRange;
  const size_t fit = perTarget > 0 ? size_t(range / perTarget) : 0;
  morphTargetCount_ = uint32_t(std::min<size_t>({mesh.morphTargets.size(), fit, 0xffffu}));
  if (morphTargetCount_ == 0) return Status::success();
  std::vector<float> deltas(size_t(morphTargetCount_) * n * kMorphDeltaFloats, 0.0f);
  for (size_t t = 0; t < morphTargetCount_; ++t) {
    const MorphTarget& mt = mesh.morphTargets[t];
    float* out = deltas.data() + t * n * kMorphDeltaFloats;
    for (size_t v = 0; v < n; ++v, out += kMorphDeltaFloats) {
      out[0] = mt.positionDeltas[v].x, out[1] = mt.positionDeltas[v].y, out[2] = mt.positionDeltas[v].z;
      if (!mt.normalDeltas.empty()) out[3] = mt.normalDeltas[v].x, out[4] = mt.normalDeltas[v].y, out[5] = mt.normalDeltas[v].z;
    }
  }
  Result<Buffer> buf = createDeviceBuffer(ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, deltas.data(), deltas.size() * sizeof(float));
  if (!buf) return Error{"morph deltas: " + buf.error()};
  morphBuffer_ = *buf;
  Result<VkDescriptorSetLayout> layout = createMorphSetLayout(device_);
  if (!layout) return Error{layout.error()};
  morphLayout_ = *layout;
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  AM_VK_TRY(vkCreateDescriptorPool(device_, &pi, nullptr, &morphPool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = morphPool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &morphLayout_;
  AM_VK_TRY(vkAllocateDescriptorSets(device_, &ai, &morphSet_), "vkAllocateDescriptorSets");
  VkDescriptorBufferInfo info{morphBuffer_.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, morphSet_, AM_MORPH_BINDING_DELTAS, 0, 1,
                         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &info, nullptr};
  vkUpdateDescriptorSets(device_, 1, &w, 0, nullptr);
  return Status::success();
}

GpuMesh::~GpuMesh() {
  if (morphPool_) vkDestroyDescriptorPool(device_, morphPool_, nullptr);  // frees morphSet_
  if (morphLayout_) vkDestroyDescriptorSetLayout(device_, morphLayout_, nullptr);
  destroyBuffer(device_, morphBuffer_);
  destroyBuffer(device_, buffer_);
}

uint64_t GpuMesh::nextContentSerial() {
  static std::atomic<uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

void GpuMesh::setMaterials(std::span<const Material> materials, std::span<const VkDescriptorSet> textureSets) {
  contentSerial_ = nextContentSerial();
  for (GpuMeshPart& p : parts_) {
    p.factor = glm::vec4(1.0f);
    p.texture = VK_NULL_HANDLE;
    if (p.material >= 0 && size_t(p.material) < materials.size()) {
      const Material& m = materials[size_t(p.material)];
      p.factor = m.baseColorFactor;
      if (m.baseColorTexture >= 0 && size_t(m.baseColorTexture) < textureSets.size())
        p.texture = textureSets[size_t(m.baseColorTexture)];
    }
    const bool white = glm::all(glm::greaterThanEqual(glm::vec3(p.factor), glm::vec3(0.999f)));
    p.coloured = !white || p.texture != VK_NULL_HANDLE || hasVertexColors_;
  }
}

void GpuMesh::bindStreams(VkCommandBuffer cmd) const {
  VkBuffer bufs[kStreams];
  for (VkBuffer& b : bufs) b = buffer_.buffer;
  static_assert(AM_VERTEX_POSITION == 0 && AM_VERTEX_WEIGHTS1 == 5, "streams are bound as bindings 0..5");
  static_assert(AM_VERTEX_COLOR0 == AM_VERTEX_TEXCOORD0 + 1, "the material streams are bound together");
  vkCmdBindVertexBuffers(cmd, 0, 6, bufs, streamOffsets_);
  vkCmdBindVertexBuffers(cmd, AM_VERTEX_TEXCOORD0, 2, bufs + 6, streamOffsets_ + 6);
}

void GpuMesh::bindTriangles(VkCommandBuffer cmd) const {
  bindStreams(cmd);
  vkCmdBindIndexBuffer(cmd, buffer_.buffer, indexOffset_, VK_INDEX_TYPE_UINT32);
}

void GpuMesh::bindEdges(VkCommandBuffer cmd) const {
  bindStreams(cmd);
  vkCmdBindIndexBuffer(cmd, buffer_.buffer, edgeOffset_, VK_INDEX_TYPE_UINT32);
}

}  // namespace animorph::gpu
