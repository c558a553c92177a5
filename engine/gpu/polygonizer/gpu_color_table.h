#pragma once
// The GPU polygoniser's colour table (shaders/include/poly_color_main.glsl, docs/gpu-polygonizer.md
// "Colour"): what the colour pass reads besides the packed program to give each vertex the CPU's
// surface colour (field/surface_color.h). Pure C++ (no Vulkan), testable without a device.
#include <cstdint>

#include "core/field/field_program.h"
#include "core/util/result.h"
#include "gpu/polygonizer/gpu_field_program.h"

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
// the program (its linear colour, by its global id in the program). Returns the table's pool index
// (never 0: the ops come first).
uint32_t appendColorTable(const FieldProgram& program, PackedFieldPrograms& pk);

// A colour program packed after pk's programs (GpuField::colors): its ops' first record, their
// count, its threshold, and its colour table (appendColorTable).
struct ColorProgramWalk {
  uint32_t opBegin = 0, opCount = 0, table = 0;
  float threshold = 0.0f;
};
// Packs colors (a program of the same surface whose primitives carry finer colours, e.g. a morph's
// stand-ins split into their colour samples) into pk.pool after what is there, its pool indices
// relocated, then its colour table. Errors: packFieldPrograms' (prefixed "colour program").
Result<ColorProgramWalk> appendColorProgram(const FieldProgram& colors, PackedFieldPrograms& pk);

}  // namespace animorph::gpu
