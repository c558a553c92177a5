#include "util/animorph_fixtures.h"

#include <algorithm>

#include <glm/gtc/quaternion.hpp>

#include "core/doc/animorphosis_commands.h"
#include "core/doc/blobtree_commands.h"
#include "util/blob_builders.h"

namespace animorph::test {

namespace {

BlobNode frameNode(int id, const char* name, glm::vec3 translation, std::vector<BlobNode> children) {
  BlobNode f = operatorNode(NodeType::Frame, id, std::move(children));
  f.name = name;
  f.vec3Param("translation") = Vec3Track(translation);
  return f;
}

BlobNode named(BlobNode n, const char* name) {
  n.name = name;
  return n;
}

// Rest, +amplitude, rest, -amplitude, rest over one period.
QuatTrack swing(glm::vec3 axis, float amplitude, double period) {
  const glm::quat rest(1.0f, 0.0f, 0.0f, 0.0f);
  QuatTrack q(rest);
  q.setKey(0.25 * period, glm::angleAxis(amplitude, axis));
  q.setKey(0.5 * period, rest);
  q.setKey(0.75 * period, glm::angleAxis(-amplitude, axis));
  q.setKey(period, rest);
  return q;
}

}  // namespace

BlobTree walkerTree() {
  BlobNode body = frameNode(2, "body", {0, 0, 0},
                            {named(pointNode(3, {0, 0, 0}, 0.6f), "belly"), named(pointNode(4, {0.4f, 0.1f, 0}, 0.5f), "chest")});
  body.vec3Param("translation").setKey(0.5, {0, 0.08f, 0});
  body.vec3Param("translation").setKey(1.0, {0, 0, 0});
  BlobNode legL = frameNode(5, "legL", {0, 0, 0.2f}, {named(segmentNode(6, {0, 0, 0}, {0, -0.8f, 0}, 0.3f), "thighL")});
  legL.quatParam("rotation") = swing({0, 0, 1}, 0.4f, 1.0);
  BlobNode legR = frameNode(7, "legR", {0, 0, -0.2f}, {named(segmentNode(8, {0, 0, 0}, {0, -0.8f, 0}, 0.3f), "thighR")});
  legR.quatParam("rotation") = swing({0, 0, 1}, -0.4f, 1.0);
  BlobNode tail = operatorNode(NodeType::Blend, 9, {pointNode(10, {-0.6f, 0, 0}, 0.35f), pointNode(11, {-0.9f, 0.1f, 0}, 0.3f)});
  tail.name = "tail";
  tail.children[1].vec3Param("center").setKey(0.5, {-0.9f, 0.2f, 0.05f});
  BlobNode head = named(pointNode(12, {0.8f, 0.3f, 0}, 0.4f, 1.1f), "head");
  head.floatParam("radius").setKey(1.0, 0.45f);
  BlobNode root = operatorNode(NodeType::Blend, 1, {body, legL, legR, tail, head});
  root.name = "walker";
  return treeOf(root, 0.5f);
}

BlobTree flyerTree() {
  BlobNode body = frameNode(102, "body", {0, 0.1f, 0},
                            {named(pointNode(103, {0, 0, 0}, 0.55f), "belly"), named(pointNode(104, {0.45f, 0.1f, 0}, 0.5f), "chest")});
  BlobNode wingL = frameNode(105, "wingL", {0, 0.3f, 0.2f},
                             {named(triangleNode(106, {-0.3f, 0, 0}, {0.3f, 0, 0}, {0, 0, 1.0f}, 0.2f), "membraneL")});
  wingL.quatParam("rotation") = swing({1, 0, 0}, 0.6f, 0.5);
  BlobNode wingR = frameNode(107, "wingR", {0, 0.3f, -0.2f},
                             {named(triangleNode(108, {-0.3f, 0, 0}, {0.3f, 0, 0}, {0, 0, -1.0f}, 0.2f), "membraneR")});
  wingR.quatParam("rotation") = swing({1, 0, 0}, -0.6f, 0.5);
  BlobNode legs = frameNode(109, "legs", {0, -0.1f, 0},
                            {named(segmentNode(110, {0, 0, 0.15f}, {0.1f, -0.5f, 0.15f}, 0.25f), "shinL"),
                             named(segmentNode(111, {0, 0, -0.15f}, {0.1f, -0.5f, -0.15f}, 0.25f), "shinR")});
  BlobNode tail = operatorNode(NodeType::Union, 112, {pointNode(113, {-0.6f, 0, 0}, 0.35f), pointNode(114, {-0.95f, 0.05f, 0}, 0.3f),
                                                      pointNode(115, {-1.25f, 0.1f, 0}, 0.25f)});
  tail.name = "tail";
  BlobNode root = operatorNode(NodeType::Blend, 101, {body, wingL, wingR, legs, tail});
  root.name = "flyer";
  BlobTree t = treeOf(root, 0.55f);
  t.threshold.setKey(1.0, 0.5f);
  return t;
}

CorrespondenceGraph walkerToFlyerGraph() {
  CorrespondenceGraph g;
  auto link = [&](int a, int b) {
    CorrespondenceLink l;
    l.nodeA = a;
    l.nodeB = b;
    g.links.push_back(l);
    return &g.links.back();
  };
  link(2, 102);                                  // body -> body
  link(2, 105)->sOverride = hermiteRampTrack(2.0f, 0.0f);  // ... and -> wingL: the body splits, the wing grows fast
  link(3, 103);
  link(4, 104);                                  // chest -> chest and -> the left membrane: split in two
  link(4, 106);
  link(6, 110);                                  // thighs -> shins inside the flyer's unlinked legs frame
  link(8, 111);
  link(9, 112);                                  // blend tail -> union tail: bridged
  link(10, 113);
  link(11, 114);                                 // bead 115 and the head grow / shrink from null partners
  return g;
}

namespace {

bool commutes(NodeType t) {
  return t == NodeType::Blend || t == NodeType::Union || t == NodeType::Intersection || t == NodeType::HyperBlend ||
         (t >= NodeType::Frame && t <= NodeType::Bend);
}

void transformNode(BlobNode& n, glm::vec3 offset, float scale, bool insideFrame, std::mt19937& rng, float jitter) {
  std::uniform_real_distribution<float> u(-jitter, jitter);
  const auto& specs = nodeTypeInfo(n.type).params;
  for (size_t i = 0; i < specs.size(); ++i) {
    std::string_view name = specs[i].name;
    auto moveTrack = [&](Vec3Track& t) {
      for (auto& k : t.keys()) {
        k.value = (insideFrame ? k.value * scale : k.value * scale + offset) + glm::vec3(u(rng), u(rng), u(rng));
        k.d1 *= scale;
        k.d2 *= scale;
      }
    };
    if (n.type >= NodeType::Twist && n.type <= NodeType::Bend) {
      if (name == "a" || name == "b") moveTrack(std::get<Vec3Track>(n.params[i]));
    } else if (n.type == NodeType::Frame) {
      if (name == "translation") moveTrack(std::get<Vec3Track>(n.params[i]));
    } else if (specs[i].kind == ParamKind::Vec3 && name != "normal" && name != "direction" && !isColorParam(specs[i])) {
      moveTrack(std::get<Vec3Track>(n.params[i]));
    } else if (specs[i].kind == ParamKind::Vec3List) {
      for (auto& p : std::get<ControlPoints>(n.params[i])) moveTrack(p);
    } else if (name == "radius" || name == "skeletonRadius" || name == "radiusA" || name == "radiusB") {
      for (auto& k : std::get<FloatTrack>(n.params[i]).keys()) k.value *= scale;
    }
  }
  for (BlobNode& c : n.children) transformNode(c, offset, scale, insideFrame || n.type == NodeType::Frame, rng, jitter);
}

void shuffleAndRenumber(BlobNode& n, std::mt19937& rng, std::unordered_map<int, int>& idMap) {
  n.id = idMap.at(n.id);
  if (commutes(n.type)) std::shuffle(n.children.begin(), n.children.end(), rng);
  for (BlobNode& c : n.children) shuffleAndRenumber(c, rng, idMap);
}

void collectIds(const BlobNode& n, std::vector<int>& ids) {
  ids.push_back(n.id);
  for (const auto& c : n.children) collectIds(c, ids);
}

}  // namespace

BlobTree perturbedCopy(const BlobTree& tree, glm::vec3 offset, float scale, std::mt19937& rng,
                       std::unordered_map<int, int>& idMap, float jitter) {
  BlobTree copy = tree;
  transformNode(copy.root, offset, scale, false, rng, jitter);
  std::vector<int> ids;
  collectIds(copy.root, ids);
  std::vector<int> fresh(ids.size());
  for (size_t i = 0; i < fresh.size(); ++i) fresh[i] = 10000 + int(i);
  std::shuffle(fresh.begin(), fresh.end(), rng);
  idMap.clear();
  for (size_t i = 0; i < ids.size(); ++i) idMap[ids[i]] = fresh[i];
  shuffleAndRenumber(copy.root, rng, idMap);
  return copy;
}

double recoveredLinks(const BlobTree& a, const CorrespondenceGraph& g, const std::unordered_map<int, int>& idMap) {
  int right = 0;
  for (const auto& l : g.links)
    if (idMap.at(l.nodeA) == l.nodeB) ++right;
  return double(right) / double(a.root.subtreeSize() - 1);
}

namespace {

BlobNode randomPart(std::mt19937& rng, int depth, int& id, int& budget, glm::vec3 centre, float spread) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  glm::vec3 p = centre + spread * glm::vec3(u(rng), u(rng), u(rng));
  if (depth <= 0 || budget <= 1) {
    --budget;
    float r = 0.15f + 0.1f * (u(rng) + 1.0f);
    if (u(rng) < 0.0f) return pointNode(id++, p, r);
    return segmentNode(id++, p, p + glm::vec3(0.2f * u(rng), -0.3f, 0.2f * u(rng)), r);
  }
  static const NodeType kinds[] = {NodeType::Blend, NodeType::Blend, NodeType::Union, NodeType::Frame};
  NodeType t = kinds[std::uniform_int_distribution<int>(0, 3)(rng)];
  BlobNode n = makeBlobNode(t, id++);
  --budget;
  if (t == NodeType::Frame) {
    n.vec3Param("translation") = Vec3Track(glm::vec3(0.1f * u(rng), 0.1f * u(rng), 0.1f * u(rng)));
    n.vec3Param("translation").setKey(1.0, glm::vec3(0.1f * u(rng), 0.1f * u(rng), 0.1f * u(rng)));
  }
  int kids = std::uniform_int_distribution<int>(2, 5)(rng);
  for (int k = 0; k < kids && budget > 0; ++k)
    n.children.push_back(randomPart(rng, depth - 1, id, budget, p, spread * 0.5f));
  if (n.children.empty()) n.children.push_back(pointNode(id++, p, 0.2f));
  return n;
}

}  // namespace

BlobTree randomCreature(std::mt19937& rng, int nodes) {
  int id = 1, budget = nodes;
  BlobNode root = makeBlobNode(NodeType::Blend, id++);
  --budget;
  while (budget > 0) root.children.push_back(randomPart(rng, 4, id, budget, glm::vec3(0.0f), 2.0f));
  return treeOf(root, 0.5f);
}

Project walkerToFlyerProject(const std::string& name, int first, int last) {
  Project p;
  p.name = name;
  p.timeline.frameStart = first;
  p.timeline.frameEnd = last;
  Actor w = makeBlobTreeActor(p, "walker");
  w.blobTree = walkerTree();
  p.actors.push_back(w);
  Actor f = makeBlobTreeActor(p, "flyer");
  f.blobTree = flyerTree();
  p.actors.push_back(f);
  auto c = createAnimorphosisCommand(p, p.actors[0].id, p.actors[1].id, 1.0, 3.0, true);
  if (c) (*c)->apply(p);
  return p;
}

}  // namespace animorph::test
