#pragma once
// The GPU polygoniser's colour table (shaders/include/poly_color_main.glsl, docs/gpu-polygonizer.md
// "Colour"): what the colour pass reads besides the packed program to give each vertex the CPU's
// surface colour (field/surface_color.h). Pure C++ (no Vulkan), testable without a device.
#include <cstdint>
#include <vector>

#include "core/field/field_program.h"
#include "core/util/result.h"
#include "gpu/polygonizer/gpu_field_program.h"
#include "gpu/polygonizer/gpu_region_op_lists.h"

namespace animorph::gpu {

// True when some primitive of program has a colour other than the clay tone (a program whose
// primitives are all clay keeps the mesh's one tone: no colour pass).
bool programHasColors(const FieldProgram& program);

// Loop iterations of the colour pass's walk of program at one vertex (shaders/include/poly_color_main.glsl):
// every op, every primitive of a Prims op stepped over, operators' operands (twice). The kernels of the
// primitives reaching the vertex's block add to it. Compared with GpuPolygonizer::loopLimit.
uint64_t colorWalkLoopEstimate(const FieldProgram& program);

// Appends program's colour table to pk.pool: one word per op (ColorProgram::emptyColor: the colour
// of the subtree the op closes where none of its primitives contributes), then one per primitive of
// the program (its linear colour, by its global id in the program), then the clay tone (a constant's
// colour), then one per space map (ColorProgram::mapEmptyColor; the region op lists' walk reads the
// last two, colorTableMaps). Returns the table's pool index (never 0: the ops come first).
uint32_t appendColorTable(const FieldProgram& program, PackedFieldPrograms& pk);
// The pool index of the maps' part of program's colour table at pool index table (the clay tone is
// the word before it).
uint32_t colorTableMaps(const FieldProgram& program, uint32_t table);

// A colour program packed after pk's programs (GpuField::colors): its ops' first record, their
// count, its threshold, its colour table (appendColorTable) and the table's maps (colorTableMaps);
// with regions, its per-region op lists (lists: their table, one uvec4 (opBegin, opCount, 0, 0) per
// region; 0: none) and the longest list's colour walk (RegionOpLists::longestColorWalk).
struct ColorProgramWalk {
  uint32_t opBegin = 0, opCount = 0, table = 0, maps = 0;
  float threshold = 0.0f;
  uint32_t lists = 0;
  uint64_t longestListWalk = 0;
};
// The regions a colour program's op lists are built for (the grid's region boxes, as the field's
// lists: gpu_region_op_lists.h), and the superblocks holding them (parentOf: each region's), whose
// lists are built first to narrow each region's candidates.
struct ColorRegions {
  const std::vector<Bounds>* regions = nullptr;
  const std::vector<Bounds>* supers = nullptr;
  const std::vector<uint32_t>* parentOf = nullptr;
};
// Packs colors (a program of the same surface whose primitives carry finer colours, e.g. a morph's
// stand-ins split into their colour samples) into pk.pool after what is there, its pool indices
// relocated, then its colour table; with where.regions, its op lists per region too (a list per
// region holding the primitives reaching it: the colour pass then walks its vertex's region's list,
// not the whole program). Errors: packFieldPrograms' (prefixed "colour program").
Result<ColorProgramWalk> appendColorProgram(const FieldProgram& colors, PackedFieldPrograms& pk,
                                            const ColorRegions& where = {});

}  // namespace animorph::gpu
