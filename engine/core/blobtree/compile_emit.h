#pragma once
// The flattening of a tree of BlobTree nodes into a FieldProgram, over any
// source of node values (blobtree/compile.h: a BlobTree's tracks at a time;
// animorphosis/compile_generic.h: the generic tree C's blended values). One
// emitter for both, so the two give the same program for the same values:
// the same ops, primitives and floats in the same order.
//
// A Source provides, for its cheap node handle Node:
//   NodeType type(Node); size_t childCount(Node); Node child(Node, size_t);
//   int& needMemo(Node)           -- memo of the evaluation stack a node needs, -1 until known;
//   float f(Node, CompileParam); glm::vec3 v(Node, CompileParam); glm::quat q(Node, CompileParam);
//   const std::vector<glm::vec3>& points(Node, CompileParam, std::vector<glm::vec3>& storage);
//   const std::vector<SpaceMap>& splineFrames(Node, std::vector<SpaceMap>& storage);
//   const std::vector<std::array<glm::vec3, 3>>& coonsTriangles(Node, std::vector<std::array<glm::vec3, 3>>& storage);
// where the storage arguments are the emitter's reused memory (a source may fill and return them,
// or return values it holds itself); values are the parameters' raw values (the emitter clamps).
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <numeric>
#include <vector>

#include "core/blobtree/node_type.h"
#include "core/field/field_program.h"

namespace animorph {

// The parameters the flattening reads.
enum class CompileParam : uint8_t {
  Center, SkeletonRadius, A, B, C, RadiusA, RadiusB, Normal, Points, Radius, Intensity, Stiffness, Sharpness, Q,
  A0, A1, A2, A3, Scale, Translation, Rotation, Angle, ScaleA, ScaleB, Direction, Count, ScaleStart, ScaleEnd,
  Bottom, Top, Left, Right, Resolution, Color, Size
};

// Index of p in nodeTypeInfo(type).params (looked up once per type, not per node); -1 where absent.
int compileParamSlot(NodeType type, CompileParam p);

template <class Source>
class FlatEmitter {
 public:
  using Node = typename Source::Node;

  FlatEmitter(FieldProgram& program, Source& source, float cutoffEpsilon)
      : prog(program), src(source), eps(cutoffEpsilon) {}

  void node(Node n) {
    const NodeType type = src.type(n);
    if (isPrimitive(type)) {
      primitive(n, type, false, false);
      return;
    }
    switch (type) {
      case NodeType::Blend: group(n, 0, OpCode::Sum); return;
      case NodeType::Union: group(n, 0, OpCode::Max); return;
      case NodeType::Intersection: {
        const size_t count = src.childCount(n);
        OrderList order(*this, n, 0);
        for (size_t i : order.v) node(src.child(n, i));
        if (count > 1) prog.addOperator(OpCode::Min, uint32_t(count));
        return;
      }
      case NodeType::HyperBlend: {
        OrderList order(*this, n, 0);
        for (size_t i : order.v) node(src.child(n, i));
        float q = std::max(1.0f, f(n, CompileParam::Q));
        prog.addOperator(OpCode::HyperBlend, uint32_t(src.childCount(n)), &q, 1);
        return;
      }
      case NodeType::Difference:
        node(src.child(n, 0));
        group(n, 1, OpCode::Max);
        prog.addOperator(OpCode::Difference, 2);
        return;
      case NodeType::RUnion:
      case NodeType::RIntersection:
        node(src.child(n, 0));
        node(src.child(n, 1));
        prog.addOperator(type == NodeType::RUnion ? OpCode::RUnion : OpCode::RIntersection, 2);
        return;
      case NodeType::BoundedBlend: {
        for (size_t i = 0; i < src.childCount(n); ++i) node(src.child(n, i));
        float a[4] = {f(n, CompileParam::A0), std::max(1e-6f, f(n, CompileParam::A1)),
                      std::max(1e-6f, f(n, CompileParam::A2)), std::max(1e-6f, f(n, CompileParam::A3))};
        prog.addOperator(OpCode::BoundedBlend, 3, a, 4);
        return;
      }
      case NodeType::Frame: {
        glm::vec3 s = v(n, CompileParam::Scale);
        for (int k = 0; k < 3; ++k)
          if (std::abs(s[k]) < 1e-6f) s[k] = s[k] < 0.0f ? -1e-6f : 1e-6f;
        prog.beginMap(makeAffineMap(v(n, CompileParam::Translation), src.q(n, CompileParam::Rotation), s));
        group(n, 0, OpCode::Sum);
        prog.endMap();
        return;
      }
      case NodeType::Twist:
        prog.beginMap(makeTwistMap(v(n, CompileParam::A), v(n, CompileParam::B), f(n, CompileParam::Angle)));
        group(n, 0, OpCode::Sum);
        prog.endMap();
        return;
      case NodeType::Taper:
        prog.beginMap(makeTaperMap(v(n, CompileParam::A), v(n, CompileParam::B),
                                   std::max(1e-4f, f(n, CompileParam::ScaleA)),
                                   std::max(1e-4f, f(n, CompileParam::ScaleB))));
        group(n, 0, OpCode::Sum);
        prog.endMap();
        return;
      case NodeType::Bend:
        prog.beginMap(makeBendMap(v(n, CompileParam::A), v(n, CompileParam::B), f(n, CompileParam::Angle),
                                  v(n, CompileParam::Direction)));
        group(n, 0, OpCode::Sum);
        prog.endMap();
        return;
      case NodeType::SplineOfNodes: {
        if (frameLevels.size() <= splineDepth) frameLevels.resize(splineDepth + 1);
        const std::vector<SpaceMap>& frames = src.splineFrames(n, frameLevels[splineDepth]);
        ++splineDepth;
        const Node child = src.child(n, 0);
        for (const SpaceMap& m : frames) {
          prog.beginMap(m);
          node(child);
          prog.endMap();
        }
        --splineDepth;
        if (frames.size() > 1) prog.addOperator(OpCode::Sum, uint32_t(frames.size()));
        return;
      }
      case NodeType::CoonsPatch: coonsPatch(n, false); return;
      default: prog.addConstant(0.0f); return;
    }
  }

 private:
  FieldProgram& prog;
  Source& src;
  float eps;
  // Reused memory: Coons triangles, curve points, one frame list per nesting level of
  // spline-of-nodes (a copy's child may itself be a spline-of-nodes).
  std::vector<std::array<glm::vec3, 3>> triangles;
  std::vector<glm::vec3> curve;
  std::vector<SkeletalPrimitive> run;  // a Coons patch's triangles
  std::deque<std::vector<SpaceMap>> frameLevels;  // a deque: deeper levels added keep references valid
  size_t splineDepth = 0;
  std::deque<std::vector<size_t>> orderLists;  // operand orders, one per nesting level in use
  size_t orderListsInUse = 0;

  float f(Node n, CompileParam p) { return src.f(n, p); }
  glm::vec3 v(Node n, CompileParam p) { return src.v(n, p); }

  static bool isPrimitive(NodeType type) { return type <= NodeType::Capsule; }

  // --- a shallow evaluation stack ---
  // Values an evaluation of a node holds on the stack at most. FieldProgram::finish folds wide
  // operators into chunks of kFoldOperands, so at most kFoldOperands - 1 values wait below an
  // operand. Operands of a commuting operator (blend, union, intersection, hyper-blend) are
  // emitted deepest first when their given order would stack more than kShallowStack values:
  // blends nested 20 deep, each holding a bead and the next blend, stack 8 values instead of 20
  // (the GPU interpreter holds 16). Orders that stack less are kept as they are (and so the
  // primitive ids, and the float order of sums).
  static constexpr int kShallowStack = 8;

  // Stack need of operands with these needs emitted in this order.
  template <class NeedOf>
  static int sequenceNeed(size_t count, NeedOf needOf) {
    int m = 1;
    for (size_t i = 0; i < count; ++i) m = std::max(m, needOf(i) + int(std::min<size_t>(i, kFoldOperands - 1)));
    return m;
  }

  // Emission order of children[first..] under a commuting operator, in a list of the emitter's
  // kept memory (lists are taken and given back in nesting order: nothing allocated once warm).
  struct OrderList {
    FlatEmitter& e;
    std::vector<size_t>& v;
    OrderList(FlatEmitter& em, Node n, size_t first) : e(em), v(em.takeOrderList()) { e.operandOrder(n, first, v); }
    ~OrderList() { --e.orderListsInUse; }
    OrderList(const OrderList&) = delete;
    OrderList& operator=(const OrderList&) = delete;
  };
  std::vector<size_t>& takeOrderList() {
    if (orderListsInUse == orderLists.size()) orderLists.emplace_back();
    return orderLists[orderListsInUse++];
  }
  void operandOrder(Node n, size_t first, std::vector<size_t>& order) {
    const size_t count = src.childCount(n);
    order.resize(count - std::min(first, count));
    std::iota(order.begin(), order.end(), first);
    if (sequenceNeed(order.size(), [&](size_t i) { return need(src.child(n, order[i])); }) > kShallowStack)
      std::stable_sort(order.begin(), order.end(),
                       [&](size_t a, size_t b) { return need(src.child(n, a)) > need(src.child(n, b)); });
  }

  int operandsNeed(Node n, size_t first) {
    OrderList order(*this, n, first);
    return sequenceNeed(order.v.size(), [&](size_t i) { return need(src.child(n, order.v[i])); });
  }

  int need(Node n) {
    const size_t count = src.childCount(n);
    if (count == 0) return 1;  // every childless node needs one value (not memoised)
    int& memo = src.needMemo(n);
    if (memo >= 0) return memo;
    int r = 1;
    switch (src.type(n)) {
      case NodeType::Blend:
      case NodeType::Union:
      case NodeType::Intersection:
      case NodeType::HyperBlend:
      case NodeType::Frame:
      case NodeType::Twist:
      case NodeType::Taper:
      case NodeType::Bend: r = operandsNeed(n, 0); break;
      case NodeType::Difference: r = std::max(need(src.child(n, 0)), 1 + operandsNeed(n, 1)); break;
      case NodeType::RUnion:
      case NodeType::RIntersection:
      case NodeType::BoundedBlend:
        for (size_t i = 0; i < count; ++i) r = std::max(r, int(i) + need(src.child(n, i)));
        break;
      case NodeType::SplineOfNodes: {
        const size_t copies = size_t(std::clamp(int(std::lround(f(n, CompileParam::Count))), 1, 1000));
        const int childNeed = need(src.child(n, 0));
        r = sequenceNeed(copies, [&](size_t) { return childNeed; });
        break;
      }
      default: break;
    }
    src.needMemo(n) = r;
    return r;
  }

  SkeletalPrimitive skeletal(Node n, NodeType type) {
    SkeletalPrimitive p;
    Skeleton& s = p.skeleton;
    switch (type) {
      case NodeType::Point: s.kind = SkeletonKind::Point; s.p0 = v(n, CompileParam::Center); break;
      case NodeType::Sphere:
        s.kind = SkeletonKind::Sphere;
        s.p0 = v(n, CompileParam::Center);
        s.r0 = std::max(0.0f, f(n, CompileParam::SkeletonRadius));
        break;
      case NodeType::Segment:
      case NodeType::Cylinder:
      case NodeType::Cone:
        s.kind = type == NodeType::Segment    ? SkeletonKind::Segment
                 : type == NodeType::Cylinder ? SkeletonKind::Cylinder
                                              : SkeletonKind::Cone;
        s.p0 = v(n, CompileParam::A);
        s.p1 = v(n, CompileParam::B);
        if (type == NodeType::Cylinder) s.r0 = std::max(0.0f, f(n, CompileParam::SkeletonRadius));
        if (type == NodeType::Cone) {
          s.r0 = std::max(0.0f, f(n, CompileParam::RadiusA));
          s.r1 = std::max(0.0f, f(n, CompileParam::RadiusB));
        }
        break;
      case NodeType::Disc:
      case NodeType::Circle: {
        s.kind = type == NodeType::Disc ? SkeletonKind::Disc : SkeletonKind::Circle;
        s.p0 = v(n, CompileParam::Center);
        glm::vec3 nn = v(n, CompileParam::Normal);
        s.p1 = glm::length(nn) > 1e-9f ? glm::normalize(nn) : glm::vec3(0, 1, 0);
        s.r0 = std::max(0.0f, f(n, CompileParam::SkeletonRadius));
        break;
      }
      case NodeType::Triangle:
        s.kind = SkeletonKind::Triangle;
        s.p0 = v(n, CompileParam::A);
        s.p1 = v(n, CompileParam::B);
        s.p2 = v(n, CompileParam::C);
        break;
      case NodeType::Curve: {
        s.kind = SkeletonKind::Curve;
        const std::vector<glm::vec3>& pts = src.points(n, CompileParam::Points, curve);
        p.curveFirst = uint32_t(prog.curvePoints.size());
        s.curveCount = int(pts.size());
        prog.curvePoints.insert(prog.curvePoints.end(), pts.begin(), pts.end());
        break;
      }
      default: break;
    }
    potential(n, p);
    return p;
  }

  // R, I and k of a skeletal primitive (or of a Coons patch's triangles).
  void potential(Node n, SkeletalPrimitive& p) {
    p.radius = std::max(0.0f, f(n, CompileParam::Radius));
    p.intensity = f(n, CompileParam::Intensity);
    p.stiffness = std::max(0.0f, f(n, CompileParam::Stiffness));
  }

  // The program's colour for the primitives n adds: its "color" parameter (sRGB, clamped) in linear
  // light; the conversion is kept for the next primitive of the same colour.
  glm::vec3 lastSrgb{-1.0f}, lastLinear{0.0f};
  void color(Node n) {
    const glm::vec3 c = v(n, CompileParam::Color);
    if (c != lastSrgb) {
      lastSrgb = c;
      lastLinear = srgbToLinear(c);
    }
    prog.nextColor = lastLinear;
  }

  // Emits a primitive; returns true when it pushed a new operand.
  bool primitive(Node n, NodeType type, bool combine, bool combineMax) {
    color(n);
    if (isSkeletalType(type)) return prog.addSkeletal(skeletal(n, type), combine, combineMax);
    if (type == NodeType::ConvSegment) {
      if (combineMax) combine = false;  // convolution ops only sum
      return prog.addConvolution(v(n, CompileParam::A), v(n, CompileParam::B),
                                 std::max(0.0f, f(n, CompileParam::Radius)),
                                 std::max(1e-6f, f(n, CompileParam::Sharpness)), eps, combine);
    }
    CapsulePrimitive c{v(n, CompileParam::A), v(n, CompileParam::B), std::max(0.0f, f(n, CompileParam::Radius))};
    return prog.addCapsule(c, combine, combineMax);
  }

  // Emits a Coons patch: the union (max) of its triangles, the first joining the previous Prims op
  // when `combine` (a union's run of primitives: max of maxes is one max, and the first triangle
  // reaching the largest value gives the gradient either way). Returns true when it pushed an operand.
  bool coonsPatch(Node n, bool combine) {
    const std::vector<std::array<glm::vec3, 3>>& tris = src.coonsTriangles(n, triangles);
    color(n);
    SkeletalPrimitive p;
    p.skeleton.kind = SkeletonKind::Triangle;
    potential(n, p);
    run.resize(tris.size(), p);
    for (size_t i = 0; i < tris.size(); ++i) {
      run[i] = p;
      run[i].skeleton.p0 = tris[i][0];
      run[i].skeleton.p1 = tris[i][1];
      run[i].skeleton.p2 = tris[i][2];
    }
    return prog.addSkeletalRun(run.data(), run.size(), combine, true);
  }

  // Emits children[first..] combined by `code` (Sum or Max) as one operand. Under a union, Coons
  // patches join the run of primitives like primitives (their triangles are max-combined).
  void group(Node n, size_t first, OpCode code) {
    uint32_t operands = 0;
    bool prevPrim = false;
    OrderList order(*this, n, first);
    for (size_t i : order.v) {
      const Node c = src.child(n, i);
      const NodeType type = src.type(c);
      if (code == OpCode::Max && type == NodeType::CoonsPatch) {
        if (coonsPatch(c, prevPrim)) ++operands;
        prevPrim = true;
      } else if (isPrimitive(type)) {
        if (primitive(c, type, prevPrim, code == OpCode::Max)) ++operands;
        prevPrim = true;
      } else {
        node(c);
        ++operands;
        prevPrim = false;
      }
    }
    if (operands == 0) prog.addConstant(0.0f);
    else if (operands > 1) prog.addOperator(code, operands);
  }
};

}  // namespace animorph
