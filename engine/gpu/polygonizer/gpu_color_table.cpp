#include "gpu/polygonizer/gpu_color_table.h"

#include <cstring>

#include "core/field/surface_color.h"

namespace animorph::gpu {

namespace {
glm::uvec4 colorWord(const glm::vec3& c) {
  glm::uvec4 w(0u);
  std::memcpy(&w.x, &c.r, 4);
  std::memcpy(&w.y, &c.g, 4);
  std::memcpy(&w.z, &c.b, 4);
  return w;
}
}  // namespace

bool programHasColors(const FieldProgram& program) {
  const glm::vec3 clay = srgbToLinear(kClayColorSrgb);
  for (const auto& cls : program.classColors)
    for (const glm::vec3& c : cls)
      if (c != clay) return true;
  return false;
}

uint64_t colorWalkLoopEstimate(const FieldProgram& program) {
  uint64_t loops = 0;
  for (const FieldOp& op : program.ops) {
    loops += 1;
    if (op.code == OpCode::Prims) loops += op.count;
    else if (op.code == OpCode::BeginMap) loops += program.primitiveCount() / 32 + 2;  // anyPrimActive's mask words
    else if (op.code != OpCode::Const && op.code != OpCode::EndMap) loops += 3 * uint64_t(op.count);
  }
  return loops;
}

uint32_t appendColorTable(const FieldProgram& program, PackedFieldPrograms& pk) {
  const ColorProgram cp(program);
  const uint32_t base = uint32_t(pk.pool.size());
  pk.pool.reserve(pk.pool.size() + cp.primColor.size() + cp.emptyColor.size());
  for (const glm::vec3& c : cp.primColor) pk.pool.push_back(colorWord(c));
  for (const glm::vec3& c : cp.emptyColor) pk.pool.push_back(colorWord(c));
  return base;
}

}  // namespace animorph::gpu
