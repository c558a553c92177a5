#include "core/animorphosis/compile_generic.h"

#include <atomic>
#include <chrono>
#include <cstring>
#include <initializer_list>
#include <thread>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/param_samplers.h"
#include "core/blobtree/compile_emit.h"
#include "core/blobtree/meta_primitives.h"

namespace animorph {

namespace {

// One node of C in pre-order, and where its values of one frame are kept.
struct PlanNode {
  const GenericNode* g = nullptr;
  uint32_t childBegin = 0, childCount = 0;  // in Impl::children
  uint32_t valueBase = 0;                   // slots in Impl::values, one per parameter
  int32_t listBase = -1;                    // slots in Impl::lists (nodes with point lists), else -1
  int32_t meta = -1;                        // Impl::frames / Impl::triangles index of a meta-primitive
  uint32_t slotsA = 0, slotsB = 0;          // A's and B's parameters in Impl::samplers
  uint32_t bridgeA = 0, bridgeB = 0;        // bridged nodes: the q of A's and B's operator
  bool movesWithA = false, movesWithB = false;  // A's / B's parameters (and q) move with their clip's time
};

// The inputs a node's values of one frame are a function of: its type, s, and the clip times of the
// sides it reads whose parameters move (0 for a side it does not read or whose tracks are constant).
// Compared bit for bit: equal keys give equal values (the samplers are pure functions of them).
struct ValueKey {
  bool valid = false;
  NodeType type = NodeType::Blend;
  uint32_t sBits = 0;
  double tA = 0.0, tB = 0.0;
  bool operator==(const ValueKey& o) const {
    return valid && o.valid && type == o.type && sBits == o.sBits && std::memcmp(&tA, &o.tA, sizeof tA) == 0 &&
           std::memcmp(&tB, &o.tB, sizeof tB) == 0;
  }
};

size_t paramCount(NodeType type) { return nodeTypeInfo(type).params.size(); }

bool hasLists(NodeType type) {
  for (const ParamSpec& p : nodeTypeInfo(type).params)
    if (p.kind == ParamKind::Vec3List) return true;
  return false;
}

double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

// Every animated track C's nodes read is precompiled once (animorphosis/param_samplers.h: each key
// segment's coefficients, a cursor on the last segment), giving Track::evaluate's values bit for bit.
struct GenericProgramCompiler::Impl {
  const GenericTree& c;
  std::vector<PlanNode> nodes;
  std::vector<uint32_t> children;
  ParamSamplers samplers;  // every node's parameter tracks, precompiled
  // One frame's values: each node's type at t, its parameters (a float in x, a vector in xyz, a
  // quaternion as x, y, z, w), point lists, meta-primitive expansions; the stack need memo.
  std::vector<NodeType> types;
  std::vector<glm::vec4> values;
  std::vector<std::vector<glm::vec3>> lists;
  std::vector<std::vector<SpaceMap>> frames;
  std::vector<std::vector<std::array<glm::vec3, 3>>> triangles;
  // Per meta-primitive: the words of the inputs its expansion was last computed from (empty: none).
  std::vector<std::vector<uint32_t>> metaInputs;
  std::vector<int> needs;
  std::vector<int8_t> paramSlots;  // compileParamSlot(type, p) at [type * CompileParam::Size + p], looked up once
  std::vector<float> sOfCurve;  // s(u) of each override curve, then of the global one (last)
  std::vector<float> splineCounts;  // a spline-of-nodes' count at this frame (the stack need reads it first)
  // Per node: the inputs its kept values were evaluated from. A node whose key is the same this
  // frame keeps them (a node outside its s(u) interval whose side's tracks are constant, a frame
  // compiled again at the same time): only nodes whose inputs moved are evaluated again.
  std::vector<ValueKey> valueKeys;
  std::atomic<uint32_t> evaluatedNodes{0};  // nodes evaluated by the compile in progress (or the last)
  bool keepValues = true;                   // GenericProgramCompiler::keepValues
  Timing timing;
  double tA = 0.0, tB = 0.0;

  // The values are evaluated in chunks of nodes (pre-order) by helper threads while the emitter
  // walks the tree; the emitter evaluates a chunk itself when it needs one nobody has taken.
  static constexpr uint32_t kChunk = 96;
  std::unique_ptr<std::atomic<uint8_t>[]> chunkState;  // 0 free, 1 taken, 2 done
  std::atomic<uint32_t> nextChunk{0};
  uint32_t chunkCount = 0;

  explicit Impl(const GenericTree& tree) : c(tree) {
    size_t valueCount = 0, listCount = 0, metaCount = 0;
    // Pre-order: each node placed before its sub-tree; its children's indices recorded once placed.
    struct Walk {
      Impl& m;
      size_t &valueCount, &listCount, &metaCount;
      uint32_t place(const GenericNode& g) {
        const uint32_t i = uint32_t(m.nodes.size());
        PlanNode p;
        p.g = &g;
        p.childCount = uint32_t(g.children.size());
        p.valueBase = uint32_t(valueCount);
        valueCount += std::max({paramCount(g.a.type), paramCount(g.b.type), size_t(1)});
        if (hasLists(g.a.type) || hasLists(g.b.type)) {
          p.listBase = int32_t(listCount);
          listCount += std::max(paramCount(g.a.type), paramCount(g.b.type));
        }
        if (g.a.type == NodeType::SplineOfNodes || g.a.type == NodeType::CoonsPatch) p.meta = int32_t(metaCount++);
        if (g.a.type != g.b.type) {
          p.slotsA = m.samplers.add(g.a);
          p.slotsB = m.samplers.add(g.b);
          p.bridgeA = m.samplers.addBridgeQ(g.a);
          p.bridgeB = m.samplers.addBridgeQ(g.b);
          p.movesWithA = m.samplers.animated(p.bridgeA, 1);
          p.movesWithB = m.samplers.animated(p.bridgeB, 1);
        } else {  // blended lists are resampled to the longer one
          std::vector<size_t> counts(std::max(g.a.params.size(), g.b.params.size()), 0);
          for (size_t k = 0; k < counts.size(); ++k) {
            auto* la = k < g.a.params.size() ? std::get_if<ControlPoints>(&g.a.params[k]) : nullptr;
            auto* lb = k < g.b.params.size() ? std::get_if<ControlPoints>(&g.b.params[k]) : nullptr;
            if (la && lb) counts[k] = std::max(la->size(), lb->size());
          }
          p.slotsA = m.samplers.add(g.a, &counts);
          p.slotsB = m.samplers.add(g.b, &counts);
        }
        p.movesWithA = p.movesWithA || m.samplers.animated(p.slotsA, uint32_t(g.a.params.size()));
        p.movesWithB = p.movesWithB || m.samplers.animated(p.slotsB, uint32_t(g.b.params.size()));
        m.nodes.push_back(p);
        std::vector<uint32_t> kids;
        kids.reserve(g.children.size());
        for (const GenericNode& k : g.children) kids.push_back(place(k));
        m.nodes[i].childBegin = uint32_t(m.children.size());
        m.children.insert(m.children.end(), kids.begin(), kids.end());
        return i;
      }
    };
    Walk{*this, valueCount, listCount, metaCount}.place(c.root);
    types.resize(nodes.size());
    values.resize(valueCount);
    lists.resize(listCount);
    frames.resize(metaCount);
    triangles.resize(metaCount);
    metaInputs.resize(metaCount);
    needs.resize(nodes.size());
    constexpr size_t kParams = size_t(CompileParam::Size);
    paramSlots.resize(allNodeTypes().size() * kParams);
    for (size_t t = 0; t < allNodeTypes().size(); ++t)
      for (size_t k = 0; k < kParams; ++k)
        paramSlots[t * kParams + k] = int8_t(compileParamSlot(NodeType(t), CompileParam(k)));
    splineCounts.resize(nodes.size());
    valueKeys.resize(nodes.size());
    chunkCount = uint32_t((nodes.size() + kChunk - 1) / kChunk);
    chunkState = std::make_unique<std::atomic<uint8_t>[]>(chunkCount);
  }

  float sOf(const GenericNode& g) const { return sOfCurve[g.sCurve >= 0 ? size_t(g.sCurve) : sOfCurve.size() - 1]; }

  // Every node's type at this frame, and each spline-of-nodes' count: what the emitter's stack
  // need reads across the tree before it emits anything (cheap: no other value).
  void prepare() {
    for (size_t i = 0; i < nodes.size(); ++i) {
      const GenericNode& g = *nodes[i].g;
      const float s = sOf(g);
      const bool bridged = g.a.type != g.b.type;
      types[i] = s <= 0.0f ? g.a.type : s >= 1.0f ? g.b.type : bridged ? NodeType::HyperBlend : g.a.type;
      if (types[i] != NodeType::SplineOfNodes) continue;
      const uint32_t k = uint32_t(compileParamSlot(NodeType::SplineOfNodes, CompileParam::Count));
      const uint32_t a = nodes[i].slotsA + k, b = nodes[i].slotsB + k;
      splineCounts[i] = s <= 0.0f   ? samplers.floatAt(a, tA)
                        : s >= 1.0f ? samplers.floatAt(b, tB)
                                    : samplers.blendFloatAt(a, b, tA, tB, s);
    }
    for (uint32_t c = 0; c < chunkCount; ++c) chunkState[c].store(0, std::memory_order_relaxed);
    evaluatedNodes.store(0, std::memory_order_relaxed);
    nextChunk.store(0, std::memory_order_release);
  }

  // Takes the next free chunk and evaluates it; false when none is left.
  bool evaluateNextChunk() {
    if (nextChunk.load(std::memory_order_relaxed) >= chunkCount) return false;  // (a waiting emitter spins here)
    const uint32_t c = nextChunk.fetch_add(1, std::memory_order_acq_rel);
    if (c >= chunkCount) return false;
    chunkState[c].store(1, std::memory_order_relaxed);
    const uint32_t end = std::min<uint32_t>(uint32_t(nodes.size()), (c + 1) * kChunk);
    uint32_t evaluated = 0;
    for (uint32_t i = c * kChunk; i < end; ++i) evaluated += evaluateIfMoved(i) ? 1 : 0;
    evaluatedNodes.fetch_add(evaluated, std::memory_order_relaxed);
    chunkState[c].store(2, std::memory_order_release);
    return true;
  }

  // Node i's values, evaluated (waiting for the thread that took its chunk, or taking chunks up to it).
  void ensure(uint32_t i) {
    const uint32_t c = i / kChunk;
    while (chunkState[c].load(std::memory_order_acquire) != 2)
      if (!evaluateNextChunk()) std::this_thread::yield();
  }

  // The inputs node i's values at this frame are a function of (ValueKey).
  ValueKey keyOf(uint32_t i) const {
    const PlanNode& p = nodes[i];
    const float s = sOf(*p.g);
    ValueKey k;
    k.valid = true;
    k.type = types[i];
    std::memcpy(&k.sBits, &s, sizeof s);
    if (s < 1.0f && p.movesWithA) k.tA = tA;  // A read: s <= 0 or blending
    if (s > 0.0f && p.movesWithB) k.tB = tB;  // B read: s >= 1 or blending
    return k;
  }

  // Node i's values at this frame: kept when its inputs are those they were evaluated from, else
  // evaluated. Returns true when evaluated.
  bool evaluateIfMoved(uint32_t i) {
    const ValueKey k = keyOf(i);
    if (k == valueKeys[i]) return false;
    valueKeys[i].valid = false;  // (a throw below leaves no stale key)
    evaluate(i);
    if (keepValues) valueKeys[i] = k;
    return true;
  }

  // Forgets every kept value: the next compile evaluates every node.
  void forgetValues() {
    for (ValueKey& k : valueKeys) k.valid = false;
  }

  // The node's values at this frame, as updateGenericSnapshot writes them into its snapshot node.
  void evaluate(uint32_t i) {
    const PlanNode& p = nodes[i];
    const GenericNode& g = *p.g;
    const float s = sOf(g);
    const bool bridged = g.a.type != g.b.type;
    const NodeType type = types[i];
    glm::vec4* out = values.data() + p.valueBase;
    const size_t params = paramCount(type);
    std::vector<glm::vec3>* nodeLists = p.listBase >= 0 ? lists.data() + p.listBase : nullptr;
    thread_local std::vector<glm::vec3> noList;
    if (bridged && s > 0.0f && s < 1.0f) {
      out[0].x = (1.0f - s) * samplers.bridgeQ(p.bridgeA, tA) + s * samplers.bridgeQ(p.bridgeB, tB);
    } else if (s <= 0.0f || s >= 1.0f) {
      const uint32_t slots = s <= 0.0f ? p.slotsA : p.slotsB;
      const double ts = s <= 0.0f ? tA : tB;
      for (uint32_t k = 0; k < params; ++k) samplers.constant(slots + k, ts, out[k], nodeLists ? nodeLists[k] : noList);
    } else {
      for (uint32_t k = 0; k < params; ++k)
        samplers.blend(p.slotsA + k, p.slotsB + k, tA, tB, s, out[k], nodeLists ? nodeLists[k] : noList);
    }
    if (type == NodeType::SplineOfNodes) {
      const std::vector<glm::vec3>& points = list(i, CompileParam::Points);
      const float count = value(i, CompileParam::Count).x, scaleStart = value(i, CompileParam::ScaleStart).x,
                  scaleEnd = value(i, CompileParam::ScaleEnd).x;
      if (!sameMetaInputs(p.meta, s, type, {&points}, {count, scaleStart, scaleEnd}))
        splineOfNodesFrames(points, count, scaleStart, scaleEnd, frames[size_t(p.meta)]);
    } else if (type == NodeType::CoonsPatch) {
      const std::vector<glm::vec3>&bottom = list(i, CompileParam::Bottom), &top = list(i, CompileParam::Top),
      &left = list(i, CompileParam::Left), &right = list(i, CompileParam::Right);
      const float resolution = value(i, CompileParam::Resolution).x;
      if (!sameMetaInputs(p.meta, s, type, {&bottom, &top, &left, &right}, {resolution})) {
        thread_local MetaScratch scratch;
        coonsPatchTriangles(bottom, top, left, right, resolution, scratch, triangles[size_t(p.meta)]);
      }
    }
  }

  // Whether a meta-primitive's inputs (its type, point lists and numbers) are bit for bit those its
  // expansion was last computed from; when not, records them. An expansion is a function of these
  // alone, so an unchanged one is kept as it is: the parts of C that stand still between frames
  // (constant tracks outside the morph) are not expanded again. A node blending its two sides
  // (0 < s < 1) has inputs that move with s: not compared, forgotten.
  bool sameMetaInputs(int32_t meta, float s, NodeType type,
                      std::initializer_list<const std::vector<glm::vec3>*> pointLists,
                      std::initializer_list<float> numbers) {
    if (s > 0.0f && s < 1.0f) {
      metaInputs[size_t(meta)].clear();
      return false;
    }
    thread_local std::vector<uint32_t> key;
    key.clear();
    key.push_back(uint32_t(type));
    for (const std::vector<glm::vec3>* l : pointLists) {
      key.push_back(uint32_t(l->size()));
      const size_t at = key.size();
      key.resize(at + 3 * l->size());
      if (!l->empty()) std::memcpy(key.data() + at, l->data(), sizeof(glm::vec3) * l->size());
    }
    for (float x : numbers) {
      uint32_t w;
      std::memcpy(&w, &x, sizeof w);
      key.push_back(w);
    }
    std::vector<uint32_t>& last = metaInputs[size_t(meta)];
    if (last == key) return true;
    last.assign(key.begin(), key.end());
    return false;
  }

  int slot(uint32_t i, CompileParam p) const {
    return paramSlots[size_t(types[i]) * size_t(CompileParam::Size) + size_t(p)];
  }
  const glm::vec4& value(uint32_t i, CompileParam p) const { return values[nodes[i].valueBase + uint32_t(slot(i, p))]; }
  const std::vector<glm::vec3>& list(uint32_t i, CompileParam p) const {
    return lists[size_t(nodes[i].listBase) + size_t(slot(i, p))];
  }
};

namespace {

// C's nodes with the values of the frame compiled (GenericProgramCompiler::Impl) as the emitter reads them.
struct PlanSource {
  using Node = uint32_t;
  GenericProgramCompiler::Impl& m;

  NodeType type(Node n) const { return m.types[n]; }
  size_t childCount(Node n) const { return m.nodes[n].childCount; }
  Node child(Node n, size_t k) const { return m.children[m.nodes[n].childBegin + k]; }
  int& needMemo(Node n) { return m.needs[n]; }
  float f(Node n, CompileParam p) const {
    if (p == CompileParam::Count && m.types[n] == NodeType::SplineOfNodes) return m.splineCounts[n];
    m.ensure(n);
    return m.value(n, p).x;
  }
  glm::vec3 v(Node n, CompileParam p) const {
    m.ensure(n);
    return glm::vec3(m.value(n, p));
  }
  glm::quat q(Node n, CompileParam p) const {
    m.ensure(n);
    const glm::vec4& x = m.value(n, p);
    return glm::quat(x.w, x.x, x.y, x.z);
  }
  const std::vector<glm::vec3>& points(Node n, CompileParam p, std::vector<glm::vec3>&) const {
    m.ensure(n);
    return m.list(n, p);
  }
  const std::vector<SpaceMap>& splineFrames(Node n, std::vector<SpaceMap>&) const {
    m.ensure(n);
    return m.frames[size_t(m.nodes[n].meta)];
  }
  const std::vector<std::array<glm::vec3, 3>>& coonsTriangles(Node n, std::vector<std::array<glm::vec3, 3>>&) const {
    m.ensure(n);
    return m.triangles[size_t(m.nodes[n].meta)];
  }
};

}  // namespace

GenericProgramCompiler::GenericProgramCompiler(const GenericTree& c) : impl_(std::make_unique<Impl>(c)) {}
GenericProgramCompiler::~GenericProgramCompiler() = default;

const GenericTree& GenericProgramCompiler::tree() const { return impl_->c; }
size_t GenericProgramCompiler::nodeCount() const { return impl_->nodes.size(); }
const GenericProgramCompiler::Timing& GenericProgramCompiler::lastTiming() const { return impl_->timing; }
size_t GenericProgramCompiler::lastEvaluatedNodes() const { return impl_->evaluatedNodes.load(); }
void GenericProgramCompiler::keepValues(bool on) {
  impl_->keepValues = on;
  if (!on) impl_->forgetValues();
}

void GenericProgramCompiler::compile(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out,
                                     const CompileOptions& options) {
  build(timing, timeSec, out, options, false);
}

RefillOutcome GenericProgramCompiler::refill(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out,
                                             const CompileOptions& options) {
  return build(timing, timeSec, out, options, true);
}

RefillOutcome GenericProgramCompiler::build(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out,
                                            const CompileOptions& options, bool refill) {
  Impl& m = *impl_;
  const auto t0 = std::chrono::steady_clock::now();
  m.tA = timing.source.localTime(timeSec);
  m.tB = timing.target.localTime(timeSec);
  const double u = timing.u(timeSec);
  m.sOfCurve.clear();
  for (const FloatTrack& curve : m.c.sCurves) m.sOfCurve.push_back(evaluateS(curve, u));
  m.sOfCurve.push_back(evaluateS(timing.globalS, u));
  m.prepare();
  std::fill(m.needs.begin(), m.needs.end(), -1);
  const auto t1 = std::chrono::steady_clock::now();
  // Helpers evaluate chunks ahead of the emitter (which takes any it reaches first).
  tbb::task_group helpers;
  const int helperCount = std::min(int(m.chunkCount), tbb::this_task_arena::max_concurrency() - 1);
  for (int h = 0; h < helperCount; ++h)
    helpers.run([&m] {
      while (m.evaluateNextChunk()) {
      }
    });
  if (refill) out.beginRefill();
  else out.reset();
  out.threshold = std::max(1e-6f, genericThreshold(m.c, timing, timeSec));
  PlanSource source{m};
  FlatEmitter<PlanSource> emitter(out, source, options.cutoffEpsilon);
  emitter.node(0);
  helpers.wait();
  const auto t2 = std::chrono::steady_clock::now();
  RefillOutcome outcome = RefillOutcome::FirstCompile;
  if (refill) outcome = out.finishRefill();
  else out.finish();
  const auto t3 = std::chrono::steady_clock::now();
  m.timing = {seconds(t0, t1), seconds(t1, t2), seconds(t2, t3)};
  return outcome;
}
}  // namespace animorph
