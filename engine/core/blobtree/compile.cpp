#include "blobtree/compile.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>
#include <unordered_map>

#include "blobtree/meta_primitives.h"

namespace animorph {

namespace {

struct Compiler {
  Compiler(FieldProgram& program, double timeSec, const CompileOptions& options)
      : prog(program), t(timeSec), opt(options) {}

  FieldProgram& prog;
  double t;
  CompileOptions opt;
  // Reused memory: meta-primitive expansion, Coons triangles, one frame list per nesting level of
  // spline-of-nodes (a copy's child may itself be a spline-of-nodes).
  MetaScratch scratch;
  std::vector<std::array<glm::vec3, 3>> triangles;
  std::deque<std::vector<SpaceMap>> frameLevels;  // a deque: deeper levels added keep references valid
  size_t splineDepth = 0;

  float f(const BlobNode& n, const char* name) const { return n.floatParam(name).evaluate(t); }
  glm::vec3 v(const BlobNode& n, const char* name) const { return n.vec3Param(name).evaluate(t); }

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
  std::unordered_map<const BlobNode*, int> needs;

  static int sequenceNeed(const std::vector<int>& operandNeeds) {
    int m = 1;
    for (size_t i = 0; i < operandNeeds.size(); ++i)
      m = std::max(m, operandNeeds[i] + int(std::min<size_t>(i, kFoldOperands - 1)));
    return m;
  }

  // Emission order of children[first..] under a commuting operator.
  std::vector<size_t> operandOrder(const std::vector<BlobNode>& children, size_t first) {
    std::vector<size_t> order(children.size() - std::min(first, children.size()));
    std::iota(order.begin(), order.end(), first);
    std::vector<int> given;
    for (size_t i : order) given.push_back(need(children[i]));
    if (sequenceNeed(given) > kShallowStack)
      std::stable_sort(order.begin(), order.end(),
                       [&](size_t a, size_t b) { return need(children[a]) > need(children[b]); });
    return order;
  }

  int operandsNeed(const std::vector<BlobNode>& children, size_t first) {
    std::vector<int> ns;
    for (size_t i : operandOrder(children, first)) ns.push_back(need(children[i]));
    return sequenceNeed(ns);
  }

  int need(const BlobNode& n) {
    if (n.children.empty()) return 1;  // every childless node needs one value (not memoised)
    if (auto it = needs.find(&n); it != needs.end()) return it->second;
    int r = 1;
    switch (n.type) {
      case NodeType::Blend:
      case NodeType::Union:
      case NodeType::Intersection:
      case NodeType::HyperBlend:
      case NodeType::Frame:
      case NodeType::Twist:
      case NodeType::Taper:
      case NodeType::Bend: r = operandsNeed(n.children, 0); break;
      case NodeType::Difference:
        if (!n.children.empty()) r = std::max(need(n.children[0]), 1 + operandsNeed(n.children, 1));
        break;
      case NodeType::RUnion:
      case NodeType::RIntersection:
      case NodeType::BoundedBlend:
        for (size_t i = 0; i < n.children.size(); ++i) r = std::max(r, int(i) + need(n.children[i]));
        break;
      case NodeType::SplineOfNodes:
        if (!n.children.empty()) {
          int copies = std::clamp(int(std::lround(f(n, "count"))), 1, 1000);
          r = sequenceNeed(std::vector<int>(size_t(copies), need(n.children[0])));
        }
        break;
      default: break;
    }
    needs[&n] = r;
    return r;
  }

  SkeletalPrimitive skeletal(const BlobNode& n) {
    SkeletalPrimitive p;
    Skeleton& s = p.skeleton;
    switch (n.type) {
      case NodeType::Point: s.kind = SkeletonKind::Point; s.p0 = v(n, "center"); break;
      case NodeType::Sphere:
        s.kind = SkeletonKind::Sphere;
        s.p0 = v(n, "center");
        s.r0 = std::max(0.0f, f(n, "skeletonRadius"));
        break;
      case NodeType::Segment: s.kind = SkeletonKind::Segment; s.p0 = v(n, "a"); s.p1 = v(n, "b"); break;
      case NodeType::Cylinder:
        s.kind = SkeletonKind::Cylinder;
        s.p0 = v(n, "a");
        s.p1 = v(n, "b");
        s.r0 = std::max(0.0f, f(n, "skeletonRadius"));
        break;
      case NodeType::Cone:
        s.kind = SkeletonKind::Cone;
        s.p0 = v(n, "a");
        s.p1 = v(n, "b");
        s.r0 = std::max(0.0f, f(n, "radiusA"));
        s.r1 = std::max(0.0f, f(n, "radiusB"));
        break;
      case NodeType::Disc:
      case NodeType::Circle: {
        s.kind = n.type == NodeType::Disc ? SkeletonKind::Disc : SkeletonKind::Circle;
        s.p0 = v(n, "center");
        glm::vec3 nn = v(n, "normal");
        s.p1 = glm::length(nn) > 1e-9f ? glm::normalize(nn) : glm::vec3(0, 1, 0);
        s.r0 = std::max(0.0f, f(n, "skeletonRadius"));
        break;
      }
      case NodeType::Triangle:
        s.kind = SkeletonKind::Triangle;
        s.p0 = v(n, "a");
        s.p1 = v(n, "b");
        s.p2 = v(n, "c");
        break;
      case NodeType::Curve: {
        s.kind = SkeletonKind::Curve;
        std::vector<glm::vec3>& pts = scratch.points[0];
        evaluatePoints(n.pointsParam("points"), t, pts);
        p.curveFirst = uint32_t(prog.curvePoints.size());
        s.curveCount = int(pts.size());
        prog.curvePoints.insert(prog.curvePoints.end(), pts.begin(), pts.end());
        break;
      }
      default: break;
    }
    p.radius = std::max(0.0f, f(n, "radius"));
    p.intensity = f(n, "intensity");
    p.stiffness = std::max(0.0f, f(n, "stiffness"));
    return p;
  }

  // Emits a primitive; returns true when it pushed a new operand.
  bool primitive(const BlobNode& n, bool combine, bool combineMax) {
    if (isSkeletalType(n.type)) return prog.addSkeletal(skeletal(n), combine, combineMax);
    if (n.type == NodeType::ConvSegment) {
      if (combineMax) combine = false;  // convolution ops only sum
      return prog.addConvolution(v(n, "a"), v(n, "b"), std::max(0.0f, f(n, "radius")),
                                 std::max(1e-6f, f(n, "sharpness")), opt.cutoffEpsilon, combine);
    }
    CapsulePrimitive c{v(n, "a"), v(n, "b"), std::max(0.0f, f(n, "radius"))};
    return prog.addCapsule(c, combine, combineMax);
  }

  // Emits a Coons patch: the union (max) of its triangles, the first joining the previous Prims op
  // when `combine` (a union's run of primitives: max of maxes is one max, and the first triangle
  // reaching the largest value gives the gradient either way). Returns true when it pushed an operand.
  bool coonsPatch(const BlobNode& n, bool combine) {
    std::vector<std::array<glm::vec3, 3>>& tris = triangles;
    coonsPatchTriangles(n, t, scratch, tris);
    SkeletalPrimitive p;
    p.skeleton.kind = SkeletonKind::Triangle;
    p.radius = std::max(0.0f, f(n, "radius"));
    p.intensity = f(n, "intensity");
    p.stiffness = std::max(0.0f, f(n, "stiffness"));
    bool pushed = false;
    for (size_t i = 0; i < tris.size(); ++i) {
      p.skeleton.p0 = tris[i][0];
      p.skeleton.p1 = tris[i][1];
      p.skeleton.p2 = tris[i][2];
      bool added = prog.addSkeletal(p, combine || i > 0, true);
      if (i == 0) pushed = added;
    }
    return pushed;
  }

  // Emits children[first..] combined by `code` (Sum or Max) as one operand. Under a union, Coons
  // patches join the run of primitives like primitives (their triangles are max-combined).
  void group(const std::vector<BlobNode>& children, size_t first, OpCode code) {
    uint32_t operands = 0;
    bool prevPrim = false;
    for (size_t i : operandOrder(children, first)) {
      const BlobNode& c = children[i];
      if (code == OpCode::Max && c.type == NodeType::CoonsPatch) {
        if (coonsPatch(c, prevPrim)) ++operands;
        prevPrim = true;
      } else if (isPrimitive(c.type)) {
        if (primitive(c, prevPrim, code == OpCode::Max)) ++operands;
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

  void node(const BlobNode& n) {
    if (isPrimitive(n.type)) {
      primitive(n, false, false);
      return;
    }
    switch (n.type) {
      case NodeType::Blend: group(n.children, 0, OpCode::Sum); return;
      case NodeType::Union: group(n.children, 0, OpCode::Max); return;
      case NodeType::Intersection:
        for (size_t i : operandOrder(n.children, 0)) node(n.children[i]);
        if (n.children.size() > 1) prog.addOperator(OpCode::Min, uint32_t(n.children.size()));
        return;
      case NodeType::HyperBlend: {
        for (size_t i : operandOrder(n.children, 0)) node(n.children[i]);
        float q = std::max(1.0f, f(n, "q"));
        prog.addOperator(OpCode::HyperBlend, uint32_t(n.children.size()), &q, 1);
        return;
      }
      case NodeType::Difference:
        node(n.children[0]);
        group(n.children, 1, OpCode::Max);
        prog.addOperator(OpCode::Difference, 2);
        return;
      case NodeType::RUnion:
      case NodeType::RIntersection:
        node(n.children[0]);
        node(n.children[1]);
        prog.addOperator(n.type == NodeType::RUnion ? OpCode::RUnion : OpCode::RIntersection, 2);
        return;
      case NodeType::BoundedBlend: {
        for (const auto& c : n.children) node(c);
        float a[4] = {f(n, "a0"), std::max(1e-6f, f(n, "a1")), std::max(1e-6f, f(n, "a2")),
                      std::max(1e-6f, f(n, "a3"))};
        prog.addOperator(OpCode::BoundedBlend, 3, a, 4);
        return;
      }
      case NodeType::Frame: {
        glm::vec3 s = v(n, "scale");
        for (int k = 0; k < 3; ++k)
          if (std::abs(s[k]) < 1e-6f) s[k] = s[k] < 0.0f ? -1e-6f : 1e-6f;
        prog.beginMap(makeAffineMap(v(n, "translation"), n.quatParam("rotation").evaluate(t), s));
        group(n.children, 0, OpCode::Sum);
        prog.endMap();
        return;
      }
      case NodeType::Twist:
        prog.beginMap(makeTwistMap(v(n, "a"), v(n, "b"), f(n, "angle")));
        group(n.children, 0, OpCode::Sum);
        prog.endMap();
        return;
      case NodeType::Taper:
        prog.beginMap(makeTaperMap(v(n, "a"), v(n, "b"), std::max(1e-4f, f(n, "scaleA")),
                                   std::max(1e-4f, f(n, "scaleB"))));
        group(n.children, 0, OpCode::Sum);
        prog.endMap();
        return;
      case NodeType::Bend:
        prog.beginMap(makeBendMap(v(n, "a"), v(n, "b"), f(n, "angle"), v(n, "direction")));
        group(n.children, 0, OpCode::Sum);
        prog.endMap();
        return;
      case NodeType::SplineOfNodes: {
        if (frameLevels.size() <= splineDepth) frameLevels.resize(splineDepth + 1);
        std::vector<SpaceMap>& frames = frameLevels[splineDepth];
        splineOfNodesFrames(n, t, scratch, frames);
        ++splineDepth;
        for (const SpaceMap& m : frames) {
          prog.beginMap(m);
          node(n.children[0]);
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
};

}  // namespace

FieldProgram compileFieldProgram(const BlobTree& tree, double timeSec, const CompileOptions& options) {
  FieldProgram prog;
  compileFieldProgram(tree, timeSec, prog, options);
  return prog;
}

void compileFieldProgram(const BlobTree& tree, double timeSec, FieldProgram& prog, const CompileOptions& options) {
  prog.reset();
  prog.threshold = std::max(1e-6f, tree.threshold.evaluate(timeSec));
  appendBlobTree(prog, tree, timeSec, options);
  prog.finish();
}

void appendBlobTree(FieldProgram& prog, const BlobTree& tree, double timeSec, const CompileOptions& options) {
  Compiler c{prog, timeSec, options};
  c.node(tree.root);
}

}  // namespace animorph
