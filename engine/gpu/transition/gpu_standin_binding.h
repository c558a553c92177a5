#pragma once
// A character's vertices bound to its stand-in (standin_morph/transition.h
// StandinBinding) and its weight map, uploaded once per prepared morph: per
// vertex two vec4, (dp_i, m_i) and (n~_i, c~_i: the stand-in colour packed as
// transition_constants.h's AM_STANDIN_COLOR_TAG says, 0 without colours), concatenated over the
// character's mesh nodes. Read as vertex stream AM_VERTEX_STANDIN_* by
// transition.vert and as a storage buffer by transition.comp.
#include <memory>
#include <vector>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/context.h"
#include "core/standin_morph/transition.h"

namespace animorph::gpu {

class GpuStandinBinding {
 public:
  static constexpr VkDeviceSize kVertexStride = 32;

  // Uploads binding with weightMap (one value per vertex, or empty: 0).
  // Errors: an empty binding, offsets/normals/weight map of different lengths,
  // Vulkan failures.
  static Result<std::unique_ptr<GpuStandinBinding>> upload(Context& ctx, const StandinBinding& binding,
                                                           const std::vector<float>& weightMap);
  ~GpuStandinBinding();
  GpuStandinBinding(const GpuStandinBinding&) = delete;
  GpuStandinBinding& operator=(const GpuStandinBinding&) = delete;

  // Binds the stream at vertex binding AM_VERTEX_STANDIN_OFFSET from vertex firstVertex on.
  void bind(VkCommandBuffer cmd, uint32_t firstVertex) const;
  VkBuffer buffer() const { return buffer_.buffer; }
  uint32_t vertexCount() const { return vertexCount_; }
  // True when the binding was uploaded with stand-in colours (drawn by the colour-fading pipelines).
  bool hasColors() const { return colored_; }

 private:
  explicit GpuStandinBinding(VkDevice device) : device_(device) {}
  VkDevice device_;
  Buffer buffer_;
  uint32_t vertexCount_ = 0;
  bool colored_ = false;
};

}  // namespace animorph::gpu
