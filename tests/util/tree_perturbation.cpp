#include "util/tree_perturbation.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/gtc/quaternion.hpp>

#include "core/blobtree/meta_primitives.h"

namespace animorph::test {

std::vector<Perturbation> allPerturbations() {
  return {Perturbation::Wrap,    Perturbation::Regroup, Perturbation::Split, Perturbation::SplineChain,
          Perturbation::DropAdd, Perturbation::Rename,  Perturbation::Place, Perturbation::Retime};
}

const char* perturbationName(Perturbation p) {
  switch (p) {
    case Perturbation::Wrap: return "wrap";
    case Perturbation::Regroup: return "regroup";
    case Perturbation::Split: return "split";
    case Perturbation::SplineChain: return "spline<->chain";
    case Perturbation::DropAdd: return "drop/add";
    case Perturbation::Rename: return "rename";
    case Perturbation::Place: return "place";
    case Perturbation::Retime: return "retime";
  }
  return "?";
}

namespace {

bool ordered(NodeType t) {
  return t == NodeType::Difference || t == NodeType::RUnion || t == NodeType::RIntersection ||
         t == NodeType::BoundedBlend || t == NodeType::SplineOfNodes || t == NodeType::Intersection;
}

bool commutes(NodeType t) {
  return t == NodeType::Blend || t == NodeType::Union || t == NodeType::Intersection || t == NodeType::HyperBlend ||
         (t >= NodeType::Frame && t <= NodeType::Bend);
}

bool isPrimitive(NodeType t) { return t <= NodeType::Capsule || t == NodeType::CoonsPatch; }

bool isSegmentLike(NodeType t) {
  return t == NodeType::Segment || t == NodeType::Cone || t == NodeType::Capsule || t == NodeType::ConvSegment ||
         t == NodeType::Cylinder;
}

// A node's place: its parent and its index there.
struct Site {
  BlobNode* parent;
  size_t index;
  BlobNode& node() const { return parent->children[index]; }
};

void collectSites(BlobNode& n, std::vector<Site>& out) {
  for (size_t i = 0; i < n.children.size(); ++i) {
    out.push_back({&n, i});
    collectSites(n.children[i], out);
  }
}

class Perturber {
 public:
  Perturber(const BlobTree& a, std::mt19937& rng) : tree_(a), rng_(rng), nextId_(a.nextId() + 1000) {
    std::vector<Site> sites;
    collectSites(tree_.root, sites);
    for (const Site& s : sites) {
      ident_[s.node().id] = {s.node().id};
      owner_[s.node().id] = s.node().id;
    }
  }

  bool edit(Perturbation p);
  PerturbedTree finish(bool rename);

 private:
  int fresh() { return nextId_++; }
  template <class F>
  std::vector<Site> sitesWhere(F&& keep) {
    std::vector<Site> all, r;
    collectSites(tree_.root, all);
    for (const Site& s : all)
      if (keep(s)) r.push_back(s);
    return r;
  }
  template <class T>
  T& pick(std::vector<T>& v) { return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng_)]; }
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
  // Node `id` of the variant, if it is (part of) a node of the original, is now the nodes `now`.
  void becomes(int id, const std::vector<int>& now) {
    auto it = owner_.find(id);
    if (it == owner_.end()) return;
    const int a = it->second;
    owner_.erase(it);
    std::vector<int>& v = ident_[a];
    v.erase(std::remove(v.begin(), v.end(), id), v.end());
    for (int n : now) {
      v.push_back(n);
      owner_[n] = a;
    }
  }

  bool wrap();
  bool regroup();
  bool split();
  bool splineToChain();
  bool chainToSpline();
  bool drop();
  bool add();
  bool place();
  bool retime();

  BlobTree tree_;
  std::mt19937& rng_;
  int nextId_;
  std::unordered_map<int, std::vector<int>> ident_;  // A id -> the variant's nodes it is
  std::unordered_map<int, int> owner_;               // variant id -> the A id it is (part of)
  int dropAddTurn_ = 0;
  // A spline made from a chain of points (by id in the variant): the original nodes its points
  // were, in order (-1: a point that was no one's), so the chain it may become again is them.
  std::unordered_map<int, std::vector<int>> chainPoints_;
};

bool Perturber::wrap() {
  auto sites = sitesWhere([](const Site& s) { return s.parent->type != NodeType::SplineOfNodes; });
  if (sites.empty()) return false;
  Site s = pick(sites);
  static const NodeType kinds[] = {NodeType::Frame, NodeType::Twist, NodeType::Blend};
  NodeType kind = kinds[std::uniform_int_distribution<int>(0, 2)(rng_)];
  BlobNode w = makeBlobNode(kind, fresh(), "wrapper");
  if (kind == NodeType::Twist) w.vec3Param("b") = Vec3Track(glm::vec3(0.0f, 1.0f, 0.0f));
  w.children.push_back(std::move(s.node()));
  s.node() = std::move(w);
  return true;
}

bool Perturber::regroup() {
  auto sites = sitesWhere([](const Site& s) {
    NodeType t = s.node().type;
    return (t == NodeType::Blend || t == NodeType::Union || t == NodeType::Frame) && s.node().children.size() >= 3;
  });
  if (sites.empty()) return false;
  BlobNode& p = pick(sites).node();
  std::vector<size_t> idx(p.children.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::shuffle(idx.begin(), idx.end(), rng_);
  size_t k = std::uniform_int_distribution<size_t>(2, p.children.size() - 1)(rng_);
  idx.resize(k);
  std::sort(idx.begin(), idx.end());
  BlobNode g = makeBlobNode(p.type == NodeType::Union ? NodeType::Union : NodeType::Blend, fresh(), "group");
  for (size_t i : idx) g.children.push_back(std::move(p.children[i]));
  for (size_t j = idx.size(); j-- > 0;) p.children.erase(p.children.begin() + long(idx[j]));
  p.children.insert(p.children.begin() + long(std::min(idx.front(), p.children.size())), std::move(g));
  return true;
}

// Keys of track `from` with each value moved a fraction f of the way to `to` at the same time.
Vec3Track between(const Vec3Track& from, const Vec3Track& to, float f) {
  Vec3Track r = from;
  for (auto& k : r.keys()) {
    k.value = glm::mix(from.evaluate(k.timeSec), to.evaluate(k.timeSec), f);
    k.userDerivatives = false;
  }
  return r;
}

bool Perturber::split() {
  auto sites = sitesWhere([](const Site& s) { return isSegmentLike(s.node().type) && !ordered(s.parent->type); });
  if (sites.empty()) return false;
  Site s = pick(sites);
  const BlobNode whole = s.node();
  const int parts = std::uniform_int_distribution<int>(2, 3)(rng_);
  std::vector<BlobNode> pieces;
  std::vector<int> ids;
  for (int i = 0; i < parts; ++i) {
    BlobNode piece = whole;
    piece.id = fresh();
    piece.name = whole.name + "_part" + std::to_string(i);
    float f0 = float(i) / parts, f1 = float(i + 1) / parts;
    piece.vec3Param("a") = between(whole.vec3Param("a"), whole.vec3Param("b"), f0);
    piece.vec3Param("b") = between(whole.vec3Param("a"), whole.vec3Param("b"), f1);
    if (whole.type == NodeType::Cone) {
      float ra = whole.floatParam("radiusA").evaluate(0.0), rb = whole.floatParam("radiusB").evaluate(0.0);
      piece.floatParam("radiusA") = FloatTrack(ra + (rb - ra) * f0);
      piece.floatParam("radiusB") = FloatTrack(ra + (rb - ra) * f1);
    }
    ids.push_back(piece.id);
    pieces.push_back(std::move(piece));
  }
  becomes(whole.id, ids);
  BlobNode* parent = s.parent;
  parent->children.erase(parent->children.begin() + long(s.index));
  parent->children.insert(parent->children.begin() + long(s.index), pieces.begin(), pieces.end());
  return true;
}

bool Perturber::splineToChain() {
  auto sites = sitesWhere([](const Site& s) {
    return s.node().type == NodeType::SplineOfNodes && s.node().children.front().type == NodeType::Point &&
           !ordered(s.parent->type);
  });
  if (sites.empty()) return false;
  Site s = pick(sites);
  const BlobNode spline = s.node();
  const BlobNode& tmpl = spline.children.front();
  std::set<double> times{0.0};
  for (const auto& p : spline.pointsParam("points"))
    for (const auto& k : p.keys()) times.insert(k.timeSec);
  const glm::vec3 centre = tmpl.vec3Param("center").evaluate(0.0);
  const float radius = tmpl.floatParam("radius").evaluate(0.0);
  std::vector<std::vector<glm::vec3>> at;  // per time, per copy
  std::vector<float> scales;
  for (double t : times) {
    std::vector<SpaceMap> frames = splineOfNodesFrames(spline, t);
    at.emplace_back();
    scales.clear();
    for (const SpaceMap& f : frames) {
      at.back().push_back(f.toWorld(centre));
      scales.push_back(glm::length(f.forwardLinear[0]));
    }
  }
  BlobNode chain = makeBlobNode(NodeType::Blend, fresh(), spline.name + "_chain");
  for (size_t i = 0; i < at.front().size(); ++i) {
    BlobNode copy = tmpl;
    copy.id = fresh();
    Vec3Track c;
    c.clearKeys();
    size_t ti = 0;
    for (double t : times) {
      const std::vector<glm::vec3>& row = at[ti++];
      c.setKey(t, row[std::min(i, row.size() - 1)]);
    }
    copy.vec3Param("center") = c;
    copy.floatParam("radius") = FloatTrack(radius * scales[std::min(i, scales.size() - 1)]);
    chain.children.push_back(std::move(copy));
  }
  // A chain turned into a spline and back: each copy stands where the point it came from stood.
  if (auto it = chainPoints_.find(spline.id); it != chainPoints_.end() && it->second.size() == chain.children.size())
    for (size_t i = 0; i < chain.children.size(); ++i)
      if (int original = it->second[i]; original >= 0) {
        ident_[original].push_back(chain.children[i].id);
        owner_[chain.children[i].id] = original;
      }
  becomes(spline.id, {chain.id});
  becomes(tmpl.id, {});
  s.node() = std::move(chain);
  return true;
}

bool Perturber::chainToSpline() {
  auto sites = sitesWhere([](const Site& s) {
    const BlobNode& n = s.node();
    if (n.type != NodeType::Blend || n.children.size() < 3 || ordered(s.parent->type)) return false;
    for (const BlobNode& c : n.children)
      if (c.type != NodeType::Point) return false;
    return true;
  });
  if (sites.empty()) return false;
  Site s = pick(sites);
  const BlobNode chain = s.node();
  BlobNode spline = makeBlobNode(NodeType::SplineOfNodes, fresh(), chain.name + "_spline");
  ControlPoints pts;
  for (const BlobNode& c : chain.children) pts.push_back(c.vec3Param("center"));
  spline.pointsParam("points") = pts;
  spline.floatParam("count") = FloatTrack(float(chain.children.size()));
  const float r0 = chain.children.front().floatParam("radius").evaluate(0.0);
  const float r1 = chain.children.back().floatParam("radius").evaluate(0.0);
  spline.floatParam("scaleEnd") = FloatTrack(r0 > 0.0f ? std::max(0.05f, r1 / r0) : 1.0f);
  BlobNode tmpl = chain.children.front();
  tmpl.id = fresh();
  tmpl.vec3Param("center") = Vec3Track(glm::vec3(0.0f));
  spline.children.push_back(std::move(tmpl));
  becomes(chain.id, {spline.id});
  std::vector<int>& originals = chainPoints_[spline.id];
  for (const BlobNode& c : chain.children) {
    auto owner = owner_.find(c.id);
    originals.push_back(owner == owner_.end() ? -1 : owner->second);
    becomes(c.id, {});
  }
  s.node() = std::move(spline);
  return true;
}

bool Perturber::drop() {
  auto sites = sitesWhere([](const Site& s) {
    return isPrimitive(s.node().type) && s.node().children.empty() && !ordered(s.parent->type) &&
           s.parent->children.size() >= 2;
  });
  if (sites.empty()) return false;
  Site s = pick(sites);
  becomes(s.node().id, {});
  s.parent->children.erase(s.parent->children.begin() + long(s.index));
  return true;
}

bool Perturber::add() {
  auto sites = sitesWhere([](const Site& s) {
    return (s.node().type == NodeType::Point || s.node().type == NodeType::Segment ||
            s.node().type == NodeType::ConvSegment || s.node().type == NodeType::Cone) &&
           !ordered(s.parent->type);
  });
  if (sites.empty()) return false;
  Site s = pick(sites);
  BlobNode extra = s.node();
  extra.id = fresh();
  extra.name = "extra";
  const float r = extra.floatParam("radius").evaluate(0.0);
  const glm::vec3 shift(uniform(-1.0f, 1.0f) * r, uniform(-1.0f, 1.0f) * r, uniform(-1.0f, 1.0f) * r);
  for (const char* name : {"center", "a", "b"}) {
    if (paramIndex(extra.type, name) < 0) continue;
    Vec3Track& v = extra.vec3Param(name);
    for (auto& k : v.keys()) k.value += shift;
  }
  for (auto& k : extra.floatParam("radius").keys()) k.value *= 0.5f;
  s.parent->children.insert(s.parent->children.begin() + long(s.index) + 1, std::move(extra));
  return true;
}

bool Perturber::place() {
  BlobNode f = makeBlobNode(NodeType::Frame, fresh(), "placed");
  f.vec3Param("translation") = Vec3Track(glm::vec3(uniform(-3.0f, 3.0f), uniform(-1.0f, 1.0f), uniform(-3.0f, 3.0f)));
  glm::vec3 axis = glm::normalize(glm::vec3(uniform(-1.0f, 1.0f), uniform(0.2f, 1.0f), uniform(-1.0f, 1.0f)));
  f.quatParam("rotation") = QuatTrack(glm::angleAxis(uniform(0.3f, 2.5f), axis));
  f.vec3Param("scale") = Vec3Track(glm::vec3(uniform(0.5f, 2.0f)));
  f.children.push_back(std::move(tree_.root));
  tree_.root = std::move(f);
  return true;
}

template <class T>
void retimeTrack(Track<T>& t, double f) {
  for (auto& k : t.keys()) {
    k.timeSec *= f;
    k.d1 = T(k.d1 * float(1.0 / f));
    k.d2 = T(k.d2 * float(1.0 / (f * f)));
  }
}

void retimeNode(BlobNode& n, double f) {
  for (ParamValue& p : n.params)
    std::visit([&](auto& v) {
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, ControlPoints>) {
        for (auto& t : v) retimeTrack(t, f);
      } else {
        retimeTrack(v, f);
      }
    }, p);
  for (BlobNode& c : n.children) retimeNode(c, f);
}

bool Perturber::retime() {
  const double f = uniform(0.0f, 1.0f) < 0.5f ? uniform(0.6f, 0.8f) : uniform(1.25f, 1.6f);
  retimeNode(tree_.root, f);
  retimeTrack(tree_.threshold, f);
  return true;
}

bool Perturber::edit(Perturbation p) {
  switch (p) {
    case Perturbation::Wrap: return wrap();
    case Perturbation::Regroup: return regroup();
    case Perturbation::Split: return split();
    case Perturbation::SplineChain:
      if (uniform(0.0f, 1.0f) < 0.5f) return splineToChain() || chainToSpline();
      return chainToSpline() || splineToChain();
    case Perturbation::DropAdd: return (dropAddTurn_++ % 2 == 0) ? drop() || add() : add() || drop();
    case Perturbation::Rename: return true;
    case Perturbation::Place: return place();
    case Perturbation::Retime: return retime();
  }
  return false;
}

void renumber(BlobNode& n, std::mt19937& rng, std::unordered_map<int, int>& idMap, bool rename) {
  n.id = idMap.at(n.id);
  if (rename) n.name = "n" + std::to_string(n.id);
  if (commutes(n.type)) std::shuffle(n.children.begin(), n.children.end(), rng);
  for (BlobNode& c : n.children) renumber(c, rng, idMap, rename);
}

void collectIds(const BlobNode& n, std::vector<int>& ids) {
  ids.push_back(n.id);
  for (const BlobNode& c : n.children) collectIds(c, ids);
}

PerturbedTree Perturber::finish(bool rename) {
  std::vector<int> ids;
  collectIds(tree_.root, ids);
  std::vector<int> fresh(ids.size());
  for (size_t i = 0; i < fresh.size(); ++i) fresh[i] = 50000 + int(i);
  std::shuffle(fresh.begin(), fresh.end(), rng_);
  std::unordered_map<int, int> idMap;
  for (size_t i = 0; i < ids.size(); ++i) idMap[ids[i]] = fresh[i];
  renumber(tree_.root, rng_, idMap, rename);
  PerturbedTree out;
  for (const auto& [a, bs] : ident_) {
    std::vector<int>& v = out.identity[a];
    for (int b : bs)
      if (idMap.count(b)) v.push_back(idMap.at(b));
  }
  out.tree = std::move(tree_);
  return out;
}

}  // namespace

PerturbedTree perturbTree(const BlobTree& original, const std::vector<Perturbation>& kinds, int edits,
                          std::mt19937& rng) {
  Perturber p(original, rng);
  int done = 0;
  bool rename = false, placed = false, retimed = false;
  for (int i = 0; i < edits && !kinds.empty(); ++i) {
    Perturbation k = kinds[std::uniform_int_distribution<size_t>(0, kinds.size() - 1)(rng)];
    // The whole is placed and retimed once.
    if ((k == Perturbation::Place && placed) || (k == Perturbation::Retime && retimed)) continue;
    if (k == Perturbation::Rename && rename) continue;
    if (!p.edit(k)) continue;
    ++done;
    rename = rename || k == Perturbation::Rename;
    placed = placed || k == Perturbation::Place;
    retimed = retimed || k == Perturbation::Retime;
  }
  PerturbedTree out = p.finish(rename);
  out.edits = done;
  // The original's root is scored by no one (the roots always correspond).
  out.identity.erase(original.root.id);
  return out;
}

RecoveryScore scoreRecovery(const BlobTree& original, const CorrespondenceGraph& g,
                            const std::unordered_map<int, std::vector<int>>& identity) {
  RecoveryScore s;
  std::unordered_map<int, std::vector<int>> linked;
  for (const auto& l : g.links) linked[l.nodeA].push_back(l.nodeB);
  std::vector<int> ids;
  collectIds(original.root, ids);
  for (int a : ids) {
    if (a == original.root.id) continue;
    ++s.counted;
    auto it = identity.find(a);
    static const std::vector<int> none;
    const std::vector<int>& want = it == identity.end() ? none : it->second;
    const std::vector<int>& got = linked.count(a) ? linked.at(a) : none;
    if (want.empty()) {
      s.recovered += got.empty() ? 1.0 : 0.0;
    } else {
      int hit = 0;
      for (int b : want) hit += std::count(got.begin(), got.end(), b) > 0 ? 1 : 0;
      s.recovered += double(hit) / double(want.size());
    }
  }
  for (const auto& l : g.links) {
    ++s.links;
    auto it = identity.find(l.nodeA);
    bool right = it != identity.end() && std::count(it->second.begin(), it->second.end(), l.nodeB) > 0;
    s.wrongLinks += right ? 0 : 1;
  }
  for (const auto& l : g.suggestions) {
    ++s.suggestions;
    auto it = identity.find(l.nodeA);
    s.rightSuggestions += it != identity.end() && std::count(it->second.begin(), it->second.end(), l.nodeB) > 0;
  }
  s.recovered = s.counted > 0 ? s.recovered / s.counted : 1.0;
  return s;
}

}  // namespace animorph::test
