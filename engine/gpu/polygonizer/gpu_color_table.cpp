#include "gpu/polygonizer/gpu_color_table.h"

#include <cstring>

#include "poly_constants.h"

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

// The per-region op lists of colour program colors (packed as own, then moved to pool index off of
// pk.pool) appended to pk.pool: own's record bases relocated so the lists point into the moved
// records; its primitive ids stay its own, as its whole walk's.
void appendColorLists(const FieldProgram& colors, PackedFieldPrograms& own, uint32_t off, const ColorRegions& where,
                      PackedFieldPrograms& pk, ColorProgramWalk& w) {
  own.opBegin[0] += off;
  own.paramsBase[0] += off;
  own.mapsBase[0] += off;
  for (uint32_t& b : own.classBase[0]) b += off;
  own.pool = std::move(pk.pool);
  RegionOpLists lists;
  if (where.supers && where.parentOf && where.supers != where.regions) {
    const RegionOpLists parent = appendRegionOpLists(colors, nullptr, *where.supers, own, false);
    lists = appendRegionOpLists(colors, nullptr, *where.regions, own, false, &parent, where.parentOf);
  } else {
    lists = appendRegionOpLists(colors, nullptr, *where.regions, own, false);
  }
  pk.pool = std::move(own.pool);
  w.lists = lists.table;
  w.longestListWalk = lists.longestColorWalk;
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
  for (const glm::vec3& c : cp.emptyColor) pk.pool.push_back(colorWord(c));
  for (const glm::vec3& c : cp.primColor) pk.pool.push_back(colorWord(c));
  pk.pool.push_back(colorWord(srgbToLinear(kClayColorSrgb)));
  for (const glm::vec3& c : cp.mapEmptyColor) pk.pool.push_back(colorWord(c));
  return base;
}

uint32_t colorTableMaps(const FieldProgram& program, uint32_t table) {
  return table + uint32_t(program.ops.size() + program.primitiveCount()) + 1u;
}

Result<ColorProgramWalk> appendColorProgram(const FieldProgram& colors, PackedFieldPrograms& pk,
                                            const ColorRegions& where) {
  Result<PackedFieldPrograms> own = packFieldPrograms(colors);
  if (!own) return Error{"colour program: " + own.error()};
  const uint32_t off = uint32_t(pk.pool.size());
  std::vector<glm::uvec4>& pool = own->pool;
  // Relocate the pool indices its records hold (gpu_field_program.cpp, packOne): a Prims op's record
  // base, every op's parameter index (in floats), a map op's map record, a skeletal primitive's
  // first curve point. Primitive ids stay the colour program's own (its walk tests no block mask).
  for (uint32_t i = 0; i < own->opCount[0]; ++i) {
    glm::uvec4& op0 = pool[own->opBegin[0] + AM_REC_OP * i];
    glm::uvec4& op1 = pool[own->opBegin[0] + AM_REC_OP * i + 1];
    const uint32_t code = op0.x & 0xffu;
    if (code == AM_OP_PRIMS) op0.y += off;
    op1.x += 4u * off;
    if (code == AM_OP_BEGINMAP || code == AM_OP_ENDMAP) op1.y += off;
  }
  for (size_t i = 0; i < colors.skeletal.size(); ++i) pool[own->classBase[0][AM_PRIM_SKELETAL] + AM_REC_SKEL * i + 3].w += off;
  pk.pool.insert(pk.pool.end(), pool.begin(), pool.end());
  ColorProgramWalk w;
  w.opBegin = own->opBegin[0] + off;
  w.opCount = own->opCount[0];
  w.threshold = colors.threshold;
  w.table = appendColorTable(colors, pk);
  w.maps = colorTableMaps(colors, w.table);
  if (where.regions) appendColorLists(colors, *own, off, where, pk, w);
  return w;
}

}  // namespace animorph::gpu
