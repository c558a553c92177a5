#include "gpu/transition/gpu_standin_binding.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "transition_constants.h"

namespace animorph::gpu {

namespace {

// c (linear, clamped) as RGBA8 bits tagged AM_STANDIN_COLOR_TAG, read back as a float.
float packStandinColor(const glm::vec4& c) {
  auto byte = [](float x) { return uint32_t(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); };
  const uint32_t bits = byte(c.r) | byte(c.g) << 8 | byte(c.b) << 16 | uint32_t(AM_STANDIN_COLOR_TAG) << 24;
  return std::bit_cast<float>(bits);
}

}  // namespace

Result<std::unique_ptr<GpuStandinBinding>> GpuStandinBinding::upload(Context& ctx, const StandinBinding& binding,
                                                                     const std::vector<float>& weightMap) {
  const size_t n = binding.offsets.size();
  if (n == 0) return Error{"stand-in binding: no vertices"};
  if (binding.standinNormals.size() != n)
    return Error{"stand-in binding: " + std::to_string(binding.standinNormals.size()) + " normals for " +
                 std::to_string(n) + " offsets"};
  if (!weightMap.empty() && weightMap.size() != n)
    return Error{"stand-in binding: weight map of " + std::to_string(weightMap.size()) + " values for " +
                 std::to_string(n) + " vertices"};
  std::vector<glm::vec4> data(2 * n);
  for (size_t i = 0; i < n; ++i) {
    data[2 * i] = glm::vec4(binding.offsets[i], weightMap.empty() ? 0.0f : weightMap[i]);
    data[2 * i + 1] = glm::vec4(binding.standinNormals[i],
                                binding.hasColors() ? packStandinColor(binding.standinColors[i]) : 0.0f);
  }
  std::unique_ptr<GpuStandinBinding> b(new GpuStandinBinding(ctx.device()));
  Result<Buffer> buf = createDeviceBuffer(ctx, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          data.data(), data.size() * sizeof(glm::vec4));
  if (!buf) return Error{"stand-in binding: " + buf.error()};
  b->buffer_ = *buf;
  b->vertexCount_ = uint32_t(n);
  b->colored_ = binding.hasColors();
  return b;
}

GpuStandinBinding::~GpuStandinBinding() { destroyBuffer(device_, buffer_); }

void GpuStandinBinding::bind(VkCommandBuffer cmd, uint32_t firstVertex) const {
  const VkDeviceSize offset = VkDeviceSize(firstVertex) * kVertexStride;
  vkCmdBindVertexBuffers(cmd, AM_VERTEX_STANDIN_OFFSET, 1, &buffer_.buffer, &offset);
}

}  // namespace animorph::gpu
