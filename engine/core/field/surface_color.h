#pragma once
// The colour of an implicit surface at given points (docs/blobtree.md, "Colour"): each primitive
// of a FieldProgram carries a colour (FieldProgram::classColors, linear RGB); at a point, the
// program's ops are run again over (potential, colour) pairs, where each value's colour is the
// blend of its operands' colours:
//   * primitives summed in one op, blend, hyper-blend: weighted by each operand's contribution to
//     the value at the point, max(p, 0) (hyper-blend: max(p, 0)^q), so a primitive whose field is
//     0 there (beyond its reach, or faded to zero intensity) gives no colour;
//   * union / intersection (and primitives combined by max): the colour of the operand taken (the
//     larger / smaller value);
//   * difference: the kept (first) operand's colour; R-union, R-intersection, bounded blend: the
//     operands' partial derivatives (clamped >= 0) as weights; remap: the operand's colour;
//   * space maps move the point as for the field; a constant (no primitive) has the clay tone.
// Where every weight is 0, the first operand's colour is kept. The field itself is not changed
// and its kernels are reused as they are: colour costs one more walk over the primitives reaching
// each point, done per output vertex after polygonisation (not per grid point).
//
// One function for every user of surface colour: the CPU polygoniser's vertices, the GPU
// polygoniser's read-back vertices, exports, and (later) the stand-in's colour.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/field/field_program.h"

namespace animorph {

class SurfaceColorEvaluator {
 public:
  // out[i] = (linear r, g, b, 1) of the surface colour at points[i], each component in [0, 1].
  // Points are grouped into spatially close runs (sorted by a coarse cell) and each run is
  // evaluated with only the primitives reaching its box. threads: 0 = all hardware threads,
  // 1 = this thread only. A finished program is required; an empty one gives the clay tone.
  void evaluate(const FieldProgram& program, const glm::vec3* points, size_t n, glm::vec4* out, int threads = 0);
  // One point (tests, tools): the same value evaluate gives.
  glm::vec3 evaluatePoint(const FieldProgram& program, const glm::vec3& p);

 private:
  std::vector<uint32_t> order_;
  std::vector<uint64_t> keys_;
};

}  // namespace animorph
