#include "core/blobtree/tree_edit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/validate.h"

namespace animorph {

namespace {

template <class N>
N* parentOf(N& n, int id, int* index) {
  for (size_t i = 0; i < n.children.size(); ++i) {
    if (n.children[i].id == id) {
      if (index) *index = int(i);
      return &n;
    }
    if (N* p = parentOf(n.children[i], id, index)) return p;
  }
  return nullptr;
}

template <class Tree, class Out>
Out trackIn(Tree& tree, const ParamAddress& a) {
  auto* n = tree.find(a.node);
  if (!n || a.param < 0 || a.param >= int(n->params.size())) return Out{};
  auto& pv = n->params[size_t(a.param)];
  if (auto* pts = std::get_if<ControlPoints>(&pv)) {
    if (a.point < 0 || a.point >= int(pts->size())) return Out{};
    return Out{&(*pts)[size_t(a.point)]};
  }
  if (a.point >= 0) return Out{};
  if (auto* f = std::get_if<FloatTrack>(&pv)) return Out{f};
  if (auto* v = std::get_if<Vec3Track>(&pv)) return Out{v};
  if (auto* q = std::get_if<QuatTrack>(&pv)) return Out{q};
  return Out{};
}

std::string paramName(const BlobNode& n, const ParamAddress& a) {
  std::string s = nodeTypeInfo(n.type).params[size_t(a.param)].name;
  if (a.point >= 0) s += "[" + std::to_string(a.point) + "]";
  return s;
}

int maxChildren(const BlobNode& n) { return nodeTypeInfo(n.type).maxChildren; }
int minChildren(const BlobNode& n) { return nodeTypeInfo(n.type).minChildren; }

void collectIds(const BlobNode& n, std::set<int>& ids) {
  ids.insert(n.id);
  for (const auto& c : n.children) collectIds(c, ids);
}

void renumber(BlobNode& n, int& nextId) {
  n.id = nextId++;
  for (auto& c : n.children) renumber(c, nextId);
}

float clampToRule(float v, ParamRule rule) {
  switch (rule) {
    case ParamRule::NonNegative: return std::max(0.0f, v);
    case ParamRule::Positive: return std::max(1e-4f, v);
    case ParamRule::AtLeastOne: return std::max(1.0f, v);
    default: return v;
  }
}

template <class T>
Track<T>* asTrack(const TrackPtr& p) {
  if (auto* t = std::get_if<Track<T>*>(&p)) return *t;
  return nullptr;
}

Error noParam(const ParamAddress& a) {
  return Error{"node " + std::to_string(a.node) + ": no parameter #" + std::to_string(a.param) +
               (a.point >= 0 ? " point " + std::to_string(a.point) : std::string())};
}

}  // namespace

TrackPtr findTrack(BlobTree& tree, const ParamAddress& a) { return trackIn<BlobTree, TrackPtr>(tree, a); }
ConstTrackPtr findTrack(const BlobTree& tree, const ParamAddress& a) {
  return trackIn<const BlobTree, ConstTrackPtr>(tree, a);
}

int channelCount(ParamKind kind) { return kind == ParamKind::Float ? 1 : 3; }
int keyCount(const BlobTree& tree, const ParamAddress& a) { return keyCount(findTrack(tree, a)); }

bool keyAt(const BlobTree& tree, const KeyRef& k, double& timeSec, ParamSample& value) {
  return keyAt(findTrack(tree, k.param), k.key, timeSec, value);
}

bool sampleParam(const BlobTree& tree, const ParamAddress& a, double timeSec, ParamSample& value) {
  return sampleTrack(findTrack(tree, a), timeSec, value);
}

TrackSet blobTrackSet(BlobTree& tree) {
  TrackSet set;
  set.find = [&tree](const ParamAddress& a) { return findTrack(tree, a); };
  set.name = [](const ParamAddress& a) { return "node " + std::to_string(a.node); };
  set.clampValue = [&tree](const ParamAddress& a, float v) {
    const BlobNode* n = tree.find(a.node);
    if (!n || a.param < 0 || a.param >= int(nodeTypeInfo(n->type).params.size())) return v;
    return clampToRule(v, nodeTypeInfo(n->type).params[size_t(a.param)].rule);
  };
  return set;
}

bool isAnimated(const BlobTree& tree, const ParamAddress& a) { return keyCount(tree, a) >= 2; }

BlobNode* findParent(BlobTree& tree, int id, int* index) { return parentOf(tree.root, id, index); }
const BlobNode* findParent(const BlobTree& tree, int id, int* index) { return parentOf(tree.root, id, index); }

bool isInSubtree(const BlobNode& ancestor, int id) {
  if (ancestor.id == id) return true;
  for (const auto& c : ancestor.children)
    if (isInSubtree(c, id)) return true;
  return false;
}

namespace {

// Level of node id below n (n itself is at `level`); 0 when absent.
int levelOf(const BlobNode& n, int id, int level) {
  if (n.id == id) return level;
  for (const auto& c : n.children)
    if (int l = levelOf(c, id, level + 1)) return l;
  return 0;
}

// Nodes on the longest path from n down to a leaf (a leaf is 1).
int heightOf(const BlobNode& n) {
  int h = 0;
  for (const auto& c : n.children) h = std::max(h, heightOf(c));
  return h + 1;
}

// A tree saved by the editor must load again: no deeper than the JSON reader allows.
Status checkDepth(const BlobTree& tree, const BlobNode& node, const BlobNode& parent, const char* verb) {
  const int depth = levelOf(tree.root, parent.id, 1) + heightOf(node);
  if (depth <= kMaxBlobTreeDepth) return Status::success();
  return Error{std::string("cannot ") + verb + " " + describeNode(node) + " under " + describeNode(parent) +
               ": the tree would be " + std::to_string(depth) + " nodes deep, more than the " +
               std::to_string(kMaxBlobTreeDepth) + " allowed"};
}

}  // namespace

BlobNode makeDefaultNode(NodeType type, int& nextId) {
  const NodeTypeInfo& info = nodeTypeInfo(type);
  BlobNode n = makeBlobNode(type, nextId++, info.name);
  auto setF = [&](const char* name, float v) {
    if (paramIndex(type, name) >= 0) n.floatParam(name) = FloatTrack(v);
  };
  auto setV = [&](const char* name, glm::vec3 v) {
    if (paramIndex(type, name) >= 0) n.vec3Param(name) = Vec3Track(v);
  };
  // Skeletal potentials: I = 2 with T = 1 puts the surface at 0.45 R from the skeleton.
  setF("radius", type == NodeType::ConvSegment || type == NodeType::Capsule ? 0.15f : 0.5f);
  setF("intensity", 2.0f);
  setF("skeletonRadius", 0.15f);
  setF("radiusA", 0.15f);
  setF("radiusB", 0.05f);
  setV("a", {-0.3f, 0.0f, 0.0f});
  setV("b", {0.3f, 0.0f, 0.0f});
  if (type == NodeType::Triangle) {
    setV("a", {-0.3f, 0.0f, -0.2f});
    setV("b", {0.3f, 0.0f, -0.2f});
    setV("c", {0.0f, 0.0f, 0.3f});
  }
  if (type == NodeType::Twist || type == NodeType::Taper || type == NodeType::Bend) {
    setV("a", {0.0f, -0.4f, 0.0f});
    setV("b", {0.0f, 0.4f, 0.0f});
  }
  if (type == NodeType::Bend) setV("direction", {1.0f, 0.0f, 0.0f});
  auto points = [](std::initializer_list<glm::vec3> ps) {
    ControlPoints out;
    for (const auto& p : ps) out.emplace_back(p);
    return out;
  };
  if (type == NodeType::Curve) n.pointsParam("points") = points({{-0.4f, 0, 0}, {0, 0.2f, 0}, {0.4f, 0, 0}});
  if (type == NodeType::SplineOfNodes) {
    n.pointsParam("points") = points({{-0.5f, 0, 0}, {0, 0.2f, 0}, {0.5f, 0, 0}});
    n.floatParam("scaleEnd") = FloatTrack(0.6f);
  }
  if (type == NodeType::CoonsPatch) {
    n.pointsParam("bottom") = points({{-0.3f, 0, -0.3f}, {0.3f, 0, -0.3f}});
    n.pointsParam("top") = points({{-0.3f, 0, 0.3f}, {0.3f, 0, 0.3f}});
    n.pointsParam("left") = points({{-0.3f, 0, -0.3f}, {-0.3f, 0.1f, 0}, {-0.3f, 0, 0.3f}});
    n.pointsParam("right") = points({{0.3f, 0, -0.3f}, {0.3f, 0.1f, 0}, {0.3f, 0, 0.3f}});
    n.floatParam("radius") = FloatTrack(0.3f);
  }
  // Children the type needs, spread along X so each is visible.
  int need = info.minChildren;
  for (int i = 0; i < need; ++i) {
    BlobNode s = makeBlobNode(NodeType::Sphere, nextId++, "sphere");
    float x = need == 1 ? 0.0f : -0.2f + 0.4f * float(i) / float(need - 1);
    if (type == NodeType::BoundedBlend && i == 2) x = 0.0f;  // the bounding solid sits between
    s.vec3Param("center") = Vec3Track(glm::vec3(x, 0.0f, 0.0f));
    s.floatParam("skeletonRadius") = FloatTrack(type == NodeType::SplineOfNodes ? 0.05f : 0.15f);
    s.floatParam("radius") = FloatTrack(type == NodeType::SplineOfNodes ? 0.25f : 0.4f);
    s.floatParam("intensity") = FloatTrack(2.0f);
    n.children.push_back(std::move(s));
  }
  return n;
}

BlobTree makeStarterTree() {
  BlobTree t;
  int next = 1;
  t.root = makeDefaultNode(NodeType::Blend, next);
  t.root.name = "blend";
  return t;
}

Status addNode(BlobTree& tree, int parentId, BlobNode node, int index) {
  BlobNode* parent = tree.find(parentId);
  if (!parent) return Error{"no node " + std::to_string(parentId) + " to add to"};
  int mx = maxChildren(*parent);
  if (mx >= 0 && int(parent->children.size()) >= mx)
    return Error{describeNode(*parent) + " takes at most " + std::to_string(mx) + " child" + (mx == 1 ? "" : "ren")};
  std::set<int> have, adding;
  collectIds(tree.root, have);
  collectIds(node, adding);
  for (int id : adding)
    if (have.count(id)) return Error{"node id " + std::to_string(id) + " is already in use"};
  if (Status s = checkDepth(tree, node, *parent, "add"); !s) return s;
  if (index < 0 || index > int(parent->children.size())) index = int(parent->children.size());
  parent->children.insert(parent->children.begin() + index, std::move(node));
  return Status::success();
}

Status deleteNode(BlobTree& tree, int id) {
  if (tree.root.id == id) return Error{"the root node cannot be deleted"};
  int index = -1;
  BlobNode* parent = findParent(tree, id, &index);
  if (!parent) return Error{"no node " + std::to_string(id)};
  int mn = minChildren(*parent);
  if (int(parent->children.size()) - 1 < mn)
    return Error{"cannot delete " + describeNode(parent->children[size_t(index)]) + ": " + describeNode(*parent) +
                 " needs at least " + std::to_string(mn) + " child" + (mn == 1 ? "" : "ren")};
  parent->children.erase(parent->children.begin() + index);
  return Status::success();
}

Result<int> duplicateNode(BlobTree& tree, int id) {
  if (tree.root.id == id) return Error{"the root node cannot be duplicated (it has no parent)"};
  int index = -1;
  BlobNode* parent = findParent(tree, id, &index);
  if (!parent) return Error{"no node " + std::to_string(id)};
  BlobNode copy = parent->children[size_t(index)];
  int next = tree.nextId();
  renumber(copy, next);
  if (!copy.name.empty()) copy.name += " copy";
  int newId = copy.id;
  if (Status s = addNode(tree, parent->id, std::move(copy), index + 1); !s) return Error{s.error()};
  return newId;
}

Status reparentNode(BlobTree& tree, int id, int newParentId, int index) {
  if (tree.root.id == id) return Error{"the root node cannot be moved"};
  int oldIndex = -1;
  BlobNode* oldParent = findParent(tree, id, &oldIndex);
  if (!oldParent) return Error{"no node " + std::to_string(id)};
  const BlobNode& node = oldParent->children[size_t(oldIndex)];
  BlobNode* target = tree.find(newParentId);
  if (!target) return Error{"no node " + std::to_string(newParentId) + " to move to"};
  if (isInSubtree(node, newParentId))
    return Error{"cannot move " + describeNode(node) + " under " + describeNode(*target) +
                 ": it is inside the node itself (a cycle)"};
  if (oldParent == target) {
    // Reorder among siblings.
    int n = int(target->children.size());
    if (index < 0 || index >= n) index = n - 1;
    BlobNode moved = std::move(target->children[size_t(oldIndex)]);
    target->children.erase(target->children.begin() + oldIndex);
    target->children.insert(target->children.begin() + std::min(index, n - 1), std::move(moved));
    return Status::success();
  }
  int mx = maxChildren(*target);
  if (mx >= 0 && int(target->children.size()) >= mx)
    return Error{"cannot move " + describeNode(node) + ": " + describeNode(*target) + " takes at most " +
                 std::to_string(mx) + " child" + (mx == 1 ? "" : "ren")};
  if (Status s = checkDepth(tree, node, *target, "move"); !s) return s;
  int mn = minChildren(*oldParent);
  if (int(oldParent->children.size()) - 1 < mn)
    return Error{"cannot move " + describeNode(node) + ": " + describeNode(*oldParent) + " needs at least " +
                 std::to_string(mn) + " child" + (mn == 1 ? "" : "ren")};
  BlobNode moved = std::move(oldParent->children[size_t(oldIndex)]);
  oldParent->children.erase(oldParent->children.begin() + oldIndex);
  // Erasing shifted the old parent's later children (target may be one of them): look it up again.
  target = tree.find(newParentId);
  if (index < 0 || index > int(target->children.size())) index = int(target->children.size());
  target->children.insert(target->children.begin() + index, std::move(moved));
  return Status::success();
}

Status renameNode(BlobTree& tree, int id, const std::string& name) {
  BlobNode* n = tree.find(id);
  if (!n) return Error{"no node " + std::to_string(id)};
  n->name = name;
  return Status::success();
}

Status setParamValue(BlobTree& tree, const ParamAddress& a, double timeSec, const ParamSample& value, bool key) {
  BlobNode* n = tree.find(a.node);
  TrackPtr t = findTrack(tree, a);
  if (!n || std::holds_alternative<std::monostate>(t)) return noParam(a);
  const ParamSpec& spec = nodeTypeInfo(n->type).params[size_t(a.param)];
  if (!std::isfinite(timeSec)) return Error{describeNode(*n) + ": key time is not finite"};
  if (auto* f = asTrack<float>(t)) {
    const float* v = std::get_if<float>(&value);
    if (!v) return Error{describeNode(*n) + ": parameter '" + paramName(*n, a) + "' takes a number"};
    if (!std::isfinite(*v)) return Error{describeNode(*n) + ": parameter '" + paramName(*n, a) + "' must be finite"};
    setTrackValue(*f, timeSec, clampToRule(*v, spec.rule), key);
  } else if (auto* q = asTrack<glm::quat>(t)) {
    const glm::quat* v = std::get_if<glm::quat>(&value);
    if (!v) return Error{describeNode(*n) + ": parameter '" + paramName(*n, a) + "' takes a rotation"};
    if (!(glm::length(*v) > 1e-6f)) return Error{describeNode(*n) + ": parameter '" + paramName(*n, a) + "': zero quaternion"};
    setTrackValue(*q, timeSec, glm::normalize(*v), key);
  } else {
    auto* vt = asTrack<glm::vec3>(t);
    const glm::vec3* v = std::get_if<glm::vec3>(&value);
    if (!v) return Error{describeNode(*n) + ": parameter '" + paramName(*n, a) + "' takes a vector"};
    if (!std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z))
      return Error{describeNode(*n) + ": parameter '" + paramName(*n, a) + "' must be finite"};
    if (spec.rule == ParamRule::NonZero) {
      bool perComponent = n->type == NodeType::Frame;
      if (perComponent ? (v->x == 0.0f || v->y == 0.0f || v->z == 0.0f) : glm::length(*v) == 0.0f)
        return Error{describeNode(*n) + ": parameter '" + paramName(*n, a) + "' must be non-zero"};
    }
    // A colour keeps to 0..1 as floats keep to their rule.
    setTrackValue(*vt, timeSec, spec.rule == ParamRule::Color ? glm::clamp(*v, 0.0f, 1.0f) : *v, key);
  }
  return Status::success();
}

Status deleteKeys(BlobTree& tree, const std::vector<KeyRef>& keys) {
  return deleteKeys(blobTrackSet(tree), keys);
}

Result<std::vector<KeyChannelRef>> moveKeys(BlobTree& tree, const std::vector<KeyChannelRef>& channels, double dtSec,
                                            float dValue) {
  return moveKeys(blobTrackSet(tree), channels, dtSec, dValue);
}

Result<KeyChannelRef> setKeyTimeValue(BlobTree& tree, const KeyChannelRef& k, double timeSec, float value) {
  return setKeyTimeValue(blobTrackSet(tree), k, timeSec, value);
}

Status setKeyInterp(BlobTree& tree, const std::vector<KeyRef>& keys, KeyInterp interp) {
  return setKeyInterp(blobTrackSet(tree), keys, interp);
}

Status setKeyTangentMode(BlobTree& tree, const std::vector<KeyRef>& keys, bool user) {
  return setKeyTangentMode(blobTrackSet(tree), keys, user);
}

Status setKeyTangent(BlobTree& tree, const KeyChannelRef& k, float slopePerSec) {
  return setKeyTangent(blobTrackSet(tree), k, slopePerSec);
}

float keySlope(const BlobTree& tree, const KeyChannelRef& k) {
  return keySlope(findTrack(tree, k.key.param), k.key.key, k.channel);
}

namespace {
// Calls f(time) for every key of n's animated tracks (two keys or more), and its sub-tree's when recurse.
template <class F>
void eachAnimatedKeyTime(const BlobNode& n, bool recurse, F&& f) {
  auto add = [&](const auto& track) {
    if (track.keys().size() >= 2)
      for (const auto& k : track.keys()) f(k.timeSec);
  };
  for (const auto& pv : n.params) {
    if (auto* t = std::get_if<FloatTrack>(&pv)) add(*t);
    else if (auto* v = std::get_if<Vec3Track>(&pv)) add(*v);
    else if (auto* q = std::get_if<QuatTrack>(&pv)) add(*q);
    else
      for (const auto& p : std::get<ControlPoints>(pv)) add(p);
  }
  if (recurse)
    for (const auto& c : n.children) eachAnimatedKeyTime(c, true, f);
}

void keyTimesOf(const BlobNode& n, bool recurse, std::vector<double>& out) {
  eachAnimatedKeyTime(n, recurse, [&](double t) { out.push_back(t); });
}
}  // namespace

std::vector<double> animatedKeyTimes(const BlobTree& tree, int id) {
  std::vector<double> out;
  if (id < 0) {
    keyTimesOf(tree.root, true, out);
    if (tree.threshold.keys().size() >= 2)
      for (const auto& k : tree.threshold.keys()) out.push_back(k.timeSec);
  } else if (const BlobNode* n = tree.find(id)) {
    keyTimesOf(*n, false, out);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end(), [](double a, double b) { return std::abs(a - b) < kSameKeyTimeSec; }),
            out.end());
  return out;
}

double animationEndSec(const BlobTree& tree) {
  // The last of animatedKeyTimes(tree, -1), without collecting and sorting every key time: the
  // scene asks for it every frame for every looping BlobTree actor (thousands of keys on a demo creature).
  double latest = 0.0;
  bool any = false;
  auto add = [&](double t) {
    latest = any ? std::max(latest, t) : t;
    any = true;
  };
  eachAnimatedKeyTime(tree.root, true, add);
  if (tree.threshold.keys().size() >= 2)
    for (const auto& k : tree.threshold.keys()) add(k.timeSec);
  return latest;
}

}  // namespace animorph
