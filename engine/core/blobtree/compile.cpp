#include "core/blobtree/compile.h"

#include <unordered_map>

#include "core/blobtree/compile_emit.h"
#include "core/blobtree/meta_primitives.h"

namespace animorph {

int compileParamSlot(NodeType type, CompileParam p) {
  static constexpr const char* kNames[size_t(CompileParam::Size)] = {
      "center", "skeletonRadius", "a", "b", "c", "radiusA", "radiusB", "normal", "points", "radius", "intensity",
      "stiffness", "sharpness", "q", "a0", "a1", "a2", "a3", "scale", "translation", "rotation", "angle",
      "scaleA", "scaleB", "direction", "count", "scaleStart", "scaleEnd", "bottom", "top", "left", "right",
      "resolution", "color"};
  static const std::vector<std::array<int8_t, size_t(CompileParam::Size)>> slots = [] {
    std::vector<std::array<int8_t, size_t(CompileParam::Size)>> r;
    for (const NodeTypeInfo& info : allNodeTypes()) {
      r.emplace_back();
      for (size_t k = 0; k < size_t(CompileParam::Size); ++k) r.back()[k] = int8_t(paramIndex(info.type, kNames[k]));
    }
    return r;
  }();
  return slots[size_t(type)][size_t(p)];
}

namespace {

// A BlobTree's nodes with every track evaluated at one time.
struct TrackSource {
  using Node = const BlobNode*;
  double t;
  MetaScratch scratch;
  std::unordered_map<const BlobNode*, int> needs;

  template <class T>
  const Track<T>& track(Node n, CompileParam p) const {
    return std::get<Track<T>>(n->params[size_t(compileParamSlot(n->type, p))]);
  }
  NodeType type(Node n) const { return n->type; }
  size_t childCount(Node n) const { return n->children.size(); }
  Node child(Node n, size_t i) const { return &n->children[i]; }
  int& needMemo(Node n) { return needs.try_emplace(n, -1).first->second; }
  float f(Node n, CompileParam p) const { return track<float>(n, p).evaluate(t); }
  glm::vec3 v(Node n, CompileParam p) const { return track<glm::vec3>(n, p).evaluate(t); }
  glm::quat q(Node n, CompileParam p) const { return track<glm::quat>(n, p).evaluate(t); }
  const std::vector<glm::vec3>& points(Node n, CompileParam p, std::vector<glm::vec3>& storage) const {
    evaluatePoints(std::get<ControlPoints>(n->params[size_t(compileParamSlot(n->type, p))]), t, storage);
    return storage;
  }
  const std::vector<SpaceMap>& splineFrames(Node n, std::vector<SpaceMap>& storage) {
    splineOfNodesFrames(*n, t, scratch, storage);
    return storage;
  }
  const std::vector<std::array<glm::vec3, 3>>& coonsTriangles(Node n, std::vector<std::array<glm::vec3, 3>>& storage) {
    coonsPatchTriangles(*n, t, scratch, storage);
    return storage;
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

RefillOutcome refillFieldProgram(const BlobTree& tree, double timeSec, FieldProgram& prog,
                                 const CompileOptions& options) {
  prog.beginRefill();
  prog.threshold = std::max(1e-6f, tree.threshold.evaluate(timeSec));
  appendBlobTree(prog, tree, timeSec, options);
  return prog.finishRefill();
}

void appendBlobTree(FieldProgram& prog, const BlobTree& tree, double timeSec, const CompileOptions& options) {
  TrackSource source{timeSec, {}, {}};
  FlatEmitter<TrackSource> emitter(prog, source, options.cutoffEpsilon);
  emitter.node(&tree.root);
}

}  // namespace animorph
