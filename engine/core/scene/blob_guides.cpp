#include "core/scene/blob_guides.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "core/blobtree/meta_primitives.h"
#include "core/field/spline_curve.h"

namespace animorph {

namespace {

// The map a node applies to its children, if any (spline-of-nodes: copy `copy`).
bool childMap(const BlobNode& n, double t, int copy, SpaceMap& out) {
  switch (n.type) {
    case NodeType::Frame: {
      glm::vec3 s = n.vec3Param("scale").evaluate(t);
      for (int k = 0; k < 3; ++k)
        if (std::abs(s[k]) < 1e-6f) s[k] = s[k] < 0.0f ? -1e-6f : 1e-6f;
      out = makeAffineMap(n.vec3Param("translation").evaluate(t), n.quatParam("rotation").evaluate(t), s);
      return true;
    }
    case NodeType::Twist:
      out = makeTwistMap(n.vec3Param("a").evaluate(t), n.vec3Param("b").evaluate(t), n.floatParam("angle").evaluate(t));
      return true;
    case NodeType::Taper:
      out = makeTaperMap(n.vec3Param("a").evaluate(t), n.vec3Param("b").evaluate(t),
                         std::max(1e-4f, n.floatParam("scaleA").evaluate(t)),
                         std::max(1e-4f, n.floatParam("scaleB").evaluate(t)));
      return true;
    case NodeType::Bend:
      out = makeBendMap(n.vec3Param("a").evaluate(t), n.vec3Param("b").evaluate(t), n.floatParam("angle").evaluate(t),
                        n.vec3Param("direction").evaluate(t));
      return true;
    case NodeType::SplineOfNodes: {
      std::vector<SpaceMap> frames = splineOfNodesFrames(n, t);
      if (frames.empty()) return false;
      out = frames[size_t(std::clamp(copy, 0, int(frames.size()) - 1))];
      return true;
    }
    default: return false;
  }
}

bool findPath(const BlobNode& n, int id, std::vector<const BlobNode*>& path) {
  path.push_back(&n);
  if (n.id == id) return true;
  for (const auto& c : n.children)
    if (findPath(c, id, path)) return true;
  path.pop_back();
  return false;
}

struct GuideBuilder {
  BlobGuides& out;
  double t;
  float axisLength;

  void line(const NodeSpace& s, glm::vec3 a, glm::vec3 b, int node) {
    out.lines.push_back({s.toWorld(a), s.toWorld(b), node});
  }
  void marker(const NodeSpace& s, glm::vec3 p, int node) { out.markers.push_back({s.toWorld(p), node}); }
  void polyline(const NodeSpace& s, const std::vector<glm::vec3>& pts, int node, bool spline) {
    if (pts.size() < 2) return;
    if (!spline) {
      for (size_t i = 0; i + 1 < pts.size(); ++i) line(s, pts[i], pts[i + 1], node);
      return;
    }
    const int steps = 8 * int(pts.size());
    glm::vec3 prev = evaluateCurve(pts, 0.0f).position;
    for (int i = 1; i <= steps; ++i) {
      glm::vec3 p = evaluateCurve(pts, float(i) / float(steps)).position;
      line(s, prev, p, node);
      prev = p;
    }
  }
  void circle(const NodeSpace& s, glm::vec3 c, glm::vec3 normal, float r, int node) {
    if (!(r > 0.0f)) return;
    glm::vec3 nrm = glm::length(normal) > 1e-9f ? glm::normalize(normal) : glm::vec3(0, 1, 0);
    glm::vec3 u = std::abs(nrm.x) < 0.9f ? glm::normalize(glm::cross(nrm, glm::vec3(1, 0, 0)))
                                         : glm::normalize(glm::cross(nrm, glm::vec3(0, 1, 0)));
    glm::vec3 v = glm::cross(nrm, u);
    const int steps = 24;
    for (int i = 0; i < steps; ++i) {
      float a0 = 6.2831853f * float(i) / steps, a1 = 6.2831853f * float(i + 1) / steps;
      line(s, c + r * (std::cos(a0) * u + std::sin(a0) * v), c + r * (std::cos(a1) * u + std::sin(a1) * v), node);
    }
  }

  void node(const BlobNode& n, NodeSpace& s) {
    auto v = [&](const char* name) { return n.vec3Param(name).evaluate(t); };
    auto f = [&](const char* name) { return n.floatParam(name).evaluate(t); };
    auto pts = [&](const char* name) { return evaluatePoints(n.pointsParam(name), t); };
    switch (n.type) {
      case NodeType::Point: marker(s, v("center"), n.id); break;
      case NodeType::Sphere:
        marker(s, v("center"), n.id);
        circle(s, v("center"), {0, 1, 0}, f("skeletonRadius"), n.id);
        break;
      case NodeType::Segment:
      case NodeType::Cylinder:
      case NodeType::Cone:
      case NodeType::ConvSegment:
      case NodeType::Capsule:
        line(s, v("a"), v("b"), n.id);
        marker(s, v("a"), n.id);
        marker(s, v("b"), n.id);
        if (n.type == NodeType::Cylinder) {
          circle(s, v("a"), v("b") - v("a"), f("skeletonRadius"), n.id);
          circle(s, v("b"), v("b") - v("a"), f("skeletonRadius"), n.id);
        } else if (n.type == NodeType::Cone) {
          circle(s, v("a"), v("b") - v("a"), f("radiusA"), n.id);
          circle(s, v("b"), v("b") - v("a"), f("radiusB"), n.id);
        }
        break;
      case NodeType::Disc:
      case NodeType::Circle:
        marker(s, v("center"), n.id);
        circle(s, v("center"), v("normal"), f("skeletonRadius"), n.id);
        break;
      case NodeType::Triangle:
        line(s, v("a"), v("b"), n.id);
        line(s, v("b"), v("c"), n.id);
        line(s, v("c"), v("a"), n.id);
        for (const char* k : {"a", "b", "c"}) marker(s, v(k), n.id);
        break;
      case NodeType::Curve: {
        auto p = pts("points");
        polyline(s, p, n.id, true);
        for (const auto& q : p) marker(s, q, n.id);
        break;
      }
      case NodeType::CoonsPatch:
        for (const char* k : {"bottom", "top", "left", "right"}) polyline(s, pts(k), n.id, true);
        break;
      case NodeType::Frame: {
        glm::vec3 o = v("translation");
        glm::quat r = n.quatParam("rotation").evaluate(t);
        BlobGuideAxes ax;
        ax.node = n.id;
        ax.origin = s.toWorld(o);
        for (int k = 0; k < 3; ++k) {
          glm::vec3 e(0.0f);
          e[k] = axisLength;
          ax.tips[k] = s.toWorld(o + r * e);
        }
        out.axes.push_back(ax);
        break;
      }
      case NodeType::Twist:
      case NodeType::Taper:
      case NodeType::Bend:
        line(s, v("a"), v("b"), n.id);
        break;
      case NodeType::SplineOfNodes: {
        auto p = pts("points");
        polyline(s, p, n.id, true);
        for (const auto& q : p) marker(s, q, n.id);
        break;
      }
      default: break;
    }
    // Children, in the space this node maps them into.
    eachChildSpace(n, s, [&] {
      for (const auto& c : n.children) node(c, s);
    });
  }

  // Calls visit once per space n maps its children into (a spline-of-nodes: once per drawn copy,
  // its frames computed once), with that map on s.
  template <class Visit>
  void eachChildSpace(const BlobNode& n, NodeSpace& s, Visit&& visit) {
    if (n.type != NodeType::SplineOfNodes) {
      SpaceMap m;
      const bool mapped = childMap(n, t, 0, m);
      if (mapped) s.maps.push_back(m);
      visit();
      if (mapped) s.maps.pop_back();
      return;
    }
    const std::vector<SpaceMap> frames = splineOfNodesFrames(n, t);
    const int copies = std::clamp(int(std::lround(n.floatParam("count").evaluate(t))), 1, 64);
    for (int copy = 0; copy < copies; ++copy) {
      if (!frames.empty()) s.maps.push_back(frames[size_t(std::min(copy, int(frames.size()) - 1))]);
      visit();
      if (!frames.empty()) s.maps.pop_back();
    }
  }

  // The guides of path.back()'s sub-tree alone: down path[i..] through the spaces of the nodes
  // above it (every copy of a spline-of-nodes), drawing nothing of those nodes themselves.
  void along(const std::vector<const BlobNode*>& path, size_t i, NodeSpace& s) {
    if (i + 1 == path.size()) {
      node(*path[i], s);
      return;
    }
    eachChildSpace(*path[i], s, [&] { along(path, i + 1, s); });
  }
};

}  // namespace

glm::vec3 NodeSpace::toWorld(const glm::vec3& local) const {
  glm::vec3 p = local;
  for (auto it = maps.rbegin(); it != maps.rend(); ++it) p = it->toWorld(p);
  return glm::vec3(actor * glm::vec4(p, 1.0f));
}

glm::mat3 NodeSpace::jacobian(const glm::vec3& local) const {
  glm::mat3 j(1.0f);
  const float h = 1e-3f;
  for (int k = 0; k < 3; ++k) {
    glm::vec3 d(0.0f);
    d[k] = h;
    j[k] = (toWorld(local + d) - toWorld(local - d)) / (2.0f * h);
  }
  return j;
}

bool nodeSpace(const BlobTree& tree, int id, double timeSec, const glm::mat4& actor, NodeSpace& out) {
  std::vector<const BlobNode*> path;
  if (!findPath(tree.root, id, path)) return false;
  out.actor = actor;
  out.maps.clear();
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    SpaceMap m;
    if (childMap(*path[i], timeSec, 0, m)) out.maps.push_back(m);
  }
  return true;
}

BlobGuides blobGuides(const BlobTree& tree, double timeSec, const glm::mat4& actor, float axisLengthM) {
  BlobGuides g;
  NodeSpace s;
  s.actor = actor;
  GuideBuilder b{g, timeSec, axisLengthM};
  b.node(tree.root, s);
  return g;
}

BlobGuides blobSubtreeGuides(const BlobTree& tree, int nodeId, double timeSec, const glm::mat4& actor,
                             float axisLengthM) {
  BlobGuides g;
  std::vector<const BlobNode*> path;
  if (!findPath(tree.root, nodeId, path)) return g;
  NodeSpace s;
  s.actor = actor;
  GuideBuilder b{g, timeSec, axisLengthM};
  b.along(path, 0, s);
  return g;
}

BlobGuides subtreeGuides(const BlobGuides& guides, const BlobNode& top) {
  std::unordered_set<int> ids;
  std::vector<const BlobNode*> stack{&top};
  while (!stack.empty()) {
    const BlobNode* n = stack.back();
    stack.pop_back();
    ids.insert(n->id);
    for (const BlobNode& c : n->children) stack.push_back(&c);
  }
  BlobGuides out;
  out.actorId = guides.actorId;
  for (const auto& l : guides.lines)
    if (ids.count(l.node)) out.lines.push_back(l);
  for (const auto& m : guides.markers)
    if (ids.count(m.node)) out.markers.push_back(m);
  for (const auto& a : guides.axes)
    if (ids.count(a.node)) out.axes.push_back(a);
  return out;
}

}  // namespace animorph
