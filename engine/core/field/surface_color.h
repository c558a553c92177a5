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
// Where every weight is 0, the first operand's colour is kept; where none of a Prims op's
// primitives contributes, it has the colour of its first primitive. The field itself is not changed
// and its kernels are reused as they are: colour costs one more walk over the primitives reaching
// each point, done per output vertex (not per grid point); the CPU polygoniser rides it on the
// walk its normals need (evaluateActiveWithGradient: the field's gradient on the same stack).
//
// Only the primitives reaching a point can colour it (the others' field, and so their weight, is 0
// there), so the walk is restricted to them: evaluate() sorts the points into compact runs and
// specialises the program to each run's box; evaluateActive() takes a program the caller has
// already specialised to the points' region (the CPU polygoniser's per-block programs, in the
// block's own thread). A subtree that specialisation replaced by a constant keeps the colour the
// whole walk gives it there (ColorProgram::emptyColor: its colour where none of its primitives
// contributes), so both give the colours of the unrestricted walk (evaluateFull) up to float
// rounding: within 1e-5 per channel, below the 1/255 of an 8-bit colour (tests/core/surface_color.cpp).
//
// One evaluator for every user of surface colour: the CPU polygoniser's vertices, the GPU
// polygoniser's read-back vertices, exports, particles converted from a shape.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/field/field_program.h"

namespace animorph {

// A finished program with what its colour walk needs besides it, computed once per program (a
// walk over its ops and primitives) and shared read-only by every thread colouring it.
struct ColorProgram {
  // program must outlive this object.
  explicit ColorProgram(const FieldProgram& program);
  const FieldProgram& program;
  std::vector<glm::vec3> primColor;   // by global primitive id: its colour (linear)
  // By op index of program: the colour of the subtree op i closes where none of its primitives
  // contributes (what a constant standing for it in a specialised program has).
  std::vector<glm::vec3> emptyColor;
  std::vector<glm::vec3> mapEmptyColor;  // by map index: the same for the map's subtree
};

class SurfaceColorEvaluator {
 public:
  // out[i] = (linear r, g, b, 1) of the surface colour at points[i], each component in [0, 1].
  // Points are grouped into spatially close runs (sorted by a coarse cell) and each run is
  // evaluated with only the primitives reaching its box. threads: 0 = all hardware threads,
  // 1 = this thread only. A finished program is required; an empty one gives the clay tone.
  void evaluate(const FieldProgram& program, const glm::vec3* points, size_t n, glm::vec4* out, int threads = 0);
  void evaluate(const ColorProgram& program, const glm::vec3* points, size_t n, glm::vec4* out, int threads = 0);
  // One point (tests, tools): the same value evaluate gives.
  glm::vec3 evaluatePoint(const FieldProgram& program, const glm::vec3& p);
  // out[i] as evaluate gives it at (x[i], y[i], z[i]), i < n (any n >= 0), on this thread, with the
  // ops of active: program.program specialised (FieldProgram::specialise) to primitives including
  // every one whose bound reaches the points, or specialiseAll. The points are taken in runs of
  // 128 as given; map subtrees and skeletal primitives missing a run's box are skipped, so keep
  // them spatially compact.
  void evaluateActive(const ColorProgram& program, const ActiveProgram& active, const float* x, const float* y,
                      const float* z, int n, glm::vec4* out);
  // evaluateActive's colours (within float rounding: 1e-5 per channel) and, in the same walk, the
  // field and its gradient at the points: f[i] (the field minus the threshold; f may be null) and
  // (gx[i], gy[i], gz[i]) bit for bit what FieldEvaluator::evaluate gives with the same active
  // program (the walk runs the evaluator's value and gradient arithmetic, op by op in its order,
  // and calls the same kernels). For the CPU polygoniser's normals and colours in one walk instead
  // of two (a sub-block's vertices with its block's program). gx, gy, gz must not be null.
  void evaluateActiveWithGradient(const ColorProgram& program, const ActiveProgram& active, const float* x,
                                  const float* y, const float* z, int n, glm::vec4* out, float* f, float* gx,
                                  float* gy, float* gz);
  // The reference: every point against the whole program (specialiseAll), no spatial restriction
  // but the kernels' own skipping. For tests; slow on large programs.
  void evaluateFull(const FieldProgram& program, const glm::vec3* points, size_t n, glm::vec4* out);

  // One run's working memory (public only so that its type is complete here; not an interface).
  static constexpr int kRun = 128;  // points evaluated together
  struct RunScratch {
    // Stack entry s: kRun values, then kRun each of the gradient's x, y, z (written only in a walk
    // with gradients), then kRun each of r, g, b.
    std::vector<float> stack, coords, one, weight;
    // Per stack entry: its colour is uni[s] ? uc[s] at every point (its r, g, b rows unwritten) : its
    // rows; zero[s]: its value is +0 at every point (its value row unwritten). acc: a Sum's r, g, b sums.
    std::vector<uint8_t> uni, zero;
    std::vector<glm::vec3> uc;
    std::vector<float> acc;
    std::vector<uint32_t> reach;
    std::vector<uint32_t> grouped, groupStart;  // a Prims op's primitives by colour, each group's first
    std::vector<glm::vec3> groupColor;
    ActiveProgram active;
    std::vector<const float*> lx, ly, lz;  // per map level: the points
    std::vector<glm::vec3> lo, hi;         // per map level: their box
    bool grad = false;                     // this walk carries the field's gradient
    float* V(int s) { return stack.data() + size_t(s) * kRows * kRun; }
    float* G(int s, int a) { return V(s) + size_t(a + 1) * kRun; }  // gradient component a (x, y, z)
    float* C(int s, int c) { return V(s) + size_t(c + 4) * kRun; }
    static constexpr int kRows = 7;
  };

 private:
  std::vector<uint32_t> order_;
  std::vector<uint64_t> keys_;
  RunScratch run_;  // evaluateActive's and evaluateFull's
  FieldEvaluator field_;        // evaluateActiveWithGradient's gradients where the program has one colour
  std::vector<float> fScratch_;  // its values when the caller wants none
};

}  // namespace animorph
