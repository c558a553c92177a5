#pragma once
// FieldProgram: a BlobTree instantiated at one time and flattened (docs/design.md §3).
// A postfix list of operations over structure-of-arrays primitive data,
// evaluated on batches of points by FieldEvaluator: no per-point, per-node
// virtual calls. Primitives of one class under one operator form one op that
// loops over primitives outside and points inside. Every primitive carries a
// bound (compact support, or the radius where its contribution falls under
// eps * T, beyond which it is cut to exactly 0), so a region of space can use a
// specialised program holding only the primitives that reach it, with results
// identical to the full program. The value is f = p_root - T (>= 0 inside).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/field/operators.h"
#include "core/field/skeleton.h"
#include "core/field/space_map.h"
#include "core/math/bounds.h"
#include "core/math/color.h"

namespace animorph {

enum class PrimClass : uint8_t { Skeletal, Convolution, Capsule };

enum class OpCode : uint8_t {
  Prims,          // push the sum (or max) over a range of primitives of one class
  Const,          // push a constant potential (emptyValue), zero gradient
  Sum,            // pop count, push their sum (blend)
  Max,            // union
  Min,            // intersection
  HyperBlend,     // (sum p_i^q)^(1/q), q = params[param]
  Difference,     // pop 2: min(p1, 2T - p2)
  RUnion,         // pop 2: R-function union on s = p - T
  RIntersection,  // pop 2: R-function intersection
  BoundedBlend,   // pop 3 (f1, f2, bounding f3): params[param..param+3] = a0..a3
  BeginMap,       // enter maps[first]: points move to the child's space
  EndMap,         // leave maps[first]: the top gradient returns by the chain rule
  // pop 1: remapPotential (field/operators.h) with params[param] = scale, params[param + 1] = K
  // (<= 1: a plain scale). 15: the GPU's feature bit of an op code must not meet the class bits.
  Remap = 15,
};

// finish() splits Sum, Max, Min and HyperBlend ops of more operands into a chain of ops of at
// most this many (the stack of an evaluation then stays shallow however wide a blend is).
inline constexpr uint32_t kFoldOperands = 4;

struct FieldOp {
  OpCode code = OpCode::Const;
  PrimClass primClass = PrimClass::Skeletal;  // Prims
  bool combineMax = false;                    // Prims: union instead of sum (Skeletal, Capsule)
  uint32_t first = 0;         // Prims: first class-local index (in an ActiveProgram: offset in indices); maps: map index
  uint32_t count = 0;         // Prims: primitive count; operators: operand count
  uint32_t primBegin = 0;     // Prims: global id of the first primitive
  uint32_t param = 0;         // index into params
  uint32_t subtreeBegin = 0;  // first op of the subtree this op closes
  float emptyValue = 0.0f;    // potential of the subtree where no primitive contributes
};

// A skeletal primitive: g(d) = I (1 - (d/R)^2)^k of the distance to its skeleton.
struct SkeletalPrimitive {
  Skeleton skeleton;        // skeleton.curve is unused here: see curveFirst
  uint32_t curveFirst = 0;  // control points in FieldProgram::curvePoints
  float radius = 1.0f, intensity = 1.0f, stiffness = 3.0f;
};

// Where a skeletal primitive can contribute: within `reach` of segment (a, b), in its own space.
struct SkeletalReach {
  glm::vec3 a{0.0f}, b{0.0f};
  float reach = 0.0f;
};

// Convolution segments, structure of arrays: start b, unit direction a,
// length, weight w (from the radius rule), sharpness S, squared cut radius.
struct ConvolutionData {
  std::vector<float> bx, by, bz, ax, ay, az, length, weight, sharpness, cut2;
  size_t size() const { return bx.size(); }
};

// Canal surface (capsule): potential T * max(0, 2 - dist / R): equals T at
// distance R, support 2R.
struct CapsulePrimitive {
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.0f;
};

// World-space bound of one primitive: support within `radius` of segment (a, b), and a box.
struct PrimitiveBound {
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.0f;
  Bounds box;
};

// How FieldProgram::finishRefill ended: in every case the program equals a fresh compile of the same adds.
enum class RefillOutcome : uint8_t {
  Refilled,          // the adds made the kept op list again: only the values were recomputed
  FirstCompile,      // no structure was kept (never finished, reset, or malformed): a full finish ran
  StructureChanged,  // the adds made another op list: a full finish ran on it
};

// A program restricted to some primitives (see FieldProgram::specialise).
struct ActiveProgram {
  std::vector<FieldOp> ops;        // Prims ops index `indices`
  std::vector<uint32_t> indices;   // class-local primitive indices
  size_t primitiveCount = 0;
};

// Interval of a value over a region.
struct Interval {
  float lo = 0.0f, hi = 0.0f;
};

class FieldProgram {
 public:
  float threshold = 1.0f;
  std::vector<FieldOp> ops;
  std::vector<float> params;
  std::vector<SpaceMap> maps;
  std::vector<SkeletalPrimitive> skeletal;
  // Per skeletal primitive, in its own space: the capsule segment enclosing its skeleton and the
  // reach (capsule radius + primitive radius) beyond which it contributes nothing.
  std::vector<SkeletalReach> skeletalReach;
  std::vector<glm::vec3> curvePoints;
  ConvolutionData convolution;
  std::vector<CapsulePrimitive> capsules;
  std::vector<PrimitiveBound> primitiveBounds;  // by global primitive id (order of Prims ops)
  // Surface colour of each primitive (linear RGB), by class and class-local index (as a Prims op's
  // indices): every add records nextColor. Read by SurfaceColorEvaluator (field/surface_color.h);
  // the field itself never reads them.
  std::vector<glm::vec3> classColors[3];  // [PrimClass]
  // The colour the next added primitives get (reset() restores the clay tone, math/color.h).
  glm::vec3 nextColor = srgbToLinear(kClayColorSrgb);
  // Colour of a primitive of class cls, class-local index i (the clay tone when none was recorded).
  glm::vec3 primitiveColor(PrimClass cls, uint32_t i) const {
    const std::vector<glm::vec3>& c = classColors[size_t(cls)];
    return i < c.size() ? c[i] : srgbToLinear(kClayColorSrgb);
  }

  // --- building (postfix order; BlobTree's compiler and tests use these) ---
  // Each add returns true when it pushed a new operand, false when the primitive
  // joined the previous Prims op (combineWithPrevious, same class and mode).
  bool addSkeletal(const SkeletalPrimitive& p, bool combineWithPrevious, bool combineMax);
  // addSkeletal of p[0..n) in turn, the first joining the previous op when combineWithPrevious and the
  // others the first (a Coons patch's triangles): the same program, their bounds computed together.
  // Returns what addSkeletal of the first returns (false when n is 0).
  bool addSkeletalRun(const SkeletalPrimitive* p, size_t n, bool combineWithPrevious, bool combineMax);
  // Convolution segment a -> b whose long-segment surface lies at `radius`
  // (weight from the radius rule with this program's threshold); contributions
  // under eps * T are cut.
  bool addConvolution(const glm::vec3& a, const glm::vec3& b, float radius, float sharpness, float eps,
                      bool combineWithPrevious);
  bool addCapsule(const CapsulePrimitive& c, bool combineWithPrevious, bool combineMax);
  void addConstant(float potential);
  void addOperator(OpCode code, uint32_t operands, const float* opParams = nullptr, int paramCount = 0);
  void beginMap(const SpaceMap& m);
  void endMap();
  // Finishes building: empty values, subtree extents, stack sizes and bounds.
  // Call once after the last add; the program is then immutable.
  void finish();
  // Empties the program to build another one into it, keeping its memory (a scrubbing editor
  // flattens every frame into one kept program: no allocation once warm).
  void reset();
  // A refill: the same adds as a compile, for a program whose structure (op list) is kept. Empties the
  // values (as reset() does: threshold 1, the clay colour) but keeps the finished op list; the adds
  // that follow record their ops in scratch memory and the primitives, parameters, maps and bounds as
  // a compile does. Scrubbing a tree whose values alone move refills one kept program every frame.
  void beginRefill();
  // Ends a refill (instead of finish()). When the adds made the kept op list again (a 64-bit digest of
  // every op's kind, class, counts, indices and constants, and the op count, compared), only the value
  // part of finish() runs (empty values, bounds, map reaches): the folding of wide operators, the
  // subtree index and the stack sizes are kept. Otherwise the new op list replaces the kept one and a
  // full finish() runs. Either way the program then equals a fresh compile of the same adds.
  RefillOutcome finishRefill();
  // Copies other's finished structure (op list, subtree index, stack sizes, digest) into this program
  // and empties its values, so that a refill of this program can keep that structure (a new program
  // seeded from the last frame's). other unfinished or malformed: this program is reset().
  void adoptStructure(const FieldProgram& other);

  // --- queries ---
  size_t primitiveCount() const { return primitiveBounds.size(); }
  // Region where f >= 0 can occur (empty: nothing inside; unbounded(): everywhere).
  const Bounds& bounds() const { return bounds_; }
  bool unbounded() const { return unbounded_; }
  int maxStack() const { return maxStack_; }
  // Unique per finish() call (copies share it): lets evaluators cache per program.
  uint64_t identity() const { return identity_; }
  // Unique per full finish() (kept by a refill that keeps the structure, and by adoptStructure): equal
  // for two programs when their op lists, subtree indices and stack sizes are the same, so that what
  // depends only on the structure (a GPU pipeline variant, packed op records) can be kept.
  uint64_t structureIdentity() const { return structureIdentity_; }
  int maxMapDepth() const { return maxMapDepth_; }
  // World box of the supports of every primitive under maps[i] (empty: none): beyond it the
  // map's subtree has its empty value, so an evaluator may skip the subtree there.
  const Bounds& mapReach(uint32_t i) const { return mapReach_[i]; }

  // All primitives.
  void specialiseAll(ActiveProgram& out) const;
  // Only the primitives listed (sorted global ids); subtrees with none become constants.
  void specialise(const std::vector<uint32_t>& activeSorted, ActiveProgram& out) const;
  // Global ids (sorted) of primitives whose bound reaches the box.
  void primitivesReaching(const Bounds& box, std::vector<uint32_t>& out,
                          const std::vector<uint32_t>* candidates = nullptr) const;
  // bounds() shrunk by recursive subdivision (depth levels of 2x2x2): the union
  // of the boxes whose interval does not prove them outside. Still conservative.
  Bounds tightBounds(int depth = 5) const;
  // Rigorous interval of f = p - T over the ball (centre, radius) for a specialised
  // program (exact arithmetic; callers add a margin for float rounding).
  Interval interval(const ActiveProgram& prog, const glm::vec3& centre, float radius) const;
  // The last op of the outermost subtree that op i (a Prims or BeginMap) starts: ops i..end push one
  // value, ops[end].emptyValue where none of their primitives contributes (specialise).
  uint32_t subtreeEnd(uint32_t i) const { return i < outermostEnd_.size() ? outermostEnd_[i] : i; }

 private:
  bool pushPrims(PrimClass cls, uint32_t local, bool combineWithPrevious, bool combineMax, const PrimitiveBound& b);
  PrimitiveBound worldBound(const glm::vec3& a, const glm::vec3& b, float radius) const;
  // Local bounds (a capsule and its box) carried out through the open maps to world space, in place.
  void carryToWorld(PrimitiveBound* bounds, size_t n) const;
  // One bound carried out through the open maps below `level` (those above it already applied).
  void finishBound(PrimitiveBound& pb, size_t level) const;
  // Records a skeletal primitive and its reach; returns its local bound.
  PrimitiveBound pushSkeletal(const SkeletalPrimitive& p);
  std::vector<uint32_t> openMaps_;    // while building
  std::vector<uint32_t> openBegins_;  // while building: op index of each open BeginMap
  // While building, per open map: its scale when affine with a uniformly scaled rotation (a
  // primitive's capsule bound then maps to a capsule), else -1. Measured once per map, not per primitive.
  std::vector<float> openScale_;
  // While building, per open map: forwardLinear's three columns then origin, lane 3 zero (loaded
  // as four-float registers by worldBound's vector path).
  std::vector<glm::vec4> openLanes_;
  std::vector<uint32_t> outermostEnd_;
  std::vector<uint32_t> primsBefore_;  // primitives in ops[0..i): global id of the first at or after op i
  Bounds bounds_;
  bool unbounded_ = false;
  int maxStack_ = 0;
  int maxMapDepth_ = 0;
  std::vector<Bounds> mapReach_;
  uint64_t identity_ = 0;
  // The ops the adds write: ops, or refillOps_ during a refill.
  std::vector<FieldOp>& building() { return refilling_ ? refillOps_ : ops; }
  // finish()'s symbolic run over the finished ops: empty values, subtree starts, stack sizes, map
  // reaches and bounds. False when the program is malformed (not one value left).
  bool runSymbolic();
  std::vector<FieldOp> refillOps_;  // during a refill: the ops the adds made (emptied after)
  uint64_t structureDigest_ = 0;    // digest of the unfolded op list of the last full finish
  size_t builtOpCount_ = 0;         // its length
  bool refilling_ = false;          // between beginRefill and finishRefill, with a kept structure
  bool refillable_ = false;         // a finished, well-formed structure is kept
  uint64_t structureIdentity_ = 0;
};

// Evaluates programs on batches of points. Holds scratch memory: one per thread.
class FieldEvaluator {
 public:
  // f[i] = field at (x[i], y[i], z[i]); gradients when gx is non-null (gy, gz too).
  void evaluate(const FieldProgram& program, const ActiveProgram& active, const float* x, const float* y,
                const float* z, int n, float* f, float* gx = nullptr, float* gy = nullptr, float* gz = nullptr);
  // Convenience: one point, full program (slow path for tools and tests).
  float evaluatePoint(const FieldProgram& program, const glm::vec3& p, glm::vec3* gradient = nullptr);

 private:
  void runChunk(const FieldProgram& program, const ActiveProgram& active, const float* x, const float* y,
                const float* z, int n, float* f, float* gx, float* gy, float* gz);
  std::vector<float> stack_;
  std::vector<float> coords_;
  std::vector<const float*> levels_;
  std::vector<glm::vec3> levelBoxes_;  // per map level: the box of the chunk's points (lo, hi)
  ActiveProgram all_;
  uint64_t allFor_ = 0;
};

// Batched primitive kernels (field_kernels.cpp): accumulate into f (and gradients when gx != null).
void convolutionKernel(const ConvolutionData& c, const uint32_t* idx, int count, const float* x, const float* y,
                       const float* z, int n, float* f, float* gx, float* gy, float* gz);
// Per-primitive intervals of the weighted, cut convolution fields over the ball (centre, radius).
void convolutionIntervalKernel(const ConvolutionData& c, const uint32_t* idx, int count, const glm::vec3& centre,
                               float radius, float* lo, float* hi);
// [boxLo, boxHi] holds the n points: primitives that cannot reach it are skipped whole.
void skeletalKernel(const FieldProgram& prog, const uint32_t* idx, int count, bool combineMax, const float* x,
                    const float* y, const float* z, int n, const glm::vec3& boxLo, const glm::vec3& boxHi, float* f,
                    float* gx, float* gy, float* gz);
void capsuleKernel(const std::vector<CapsulePrimitive>& caps, float threshold, const uint32_t* idx, int count,
                   bool combineMax, const float* x, const float* y, const float* z, int n, float* f, float* gx,
                   float* gy, float* gz);

}  // namespace animorph
