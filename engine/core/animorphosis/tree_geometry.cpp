#include "core/animorphosis/tree_geometry.h"

#include <algorithm>
#include <string_view>

#include <glm/gtc/quaternion.hpp>

namespace animorph {

void NodeExtent::merge(const NodeExtent& o) {
  if (o.count == 0) return;
  lo = glm::min(lo, o.lo);
  hi = glm::max(hi, o.hi);
  sum += o.sum;
  count += o.count;
}

namespace {

struct Affine {
  glm::mat3 linear{1.0f};
  glm::vec3 origin{0.0f};
  glm::vec3 apply(const glm::vec3& p) const { return origin + linear * p; }
  float scale() const { return std::cbrt(std::abs(glm::determinant(linear))); }
};

bool isDirection(std::string_view name) { return name == "normal" || name == "direction"; }

void addPoint(NodeExtent& e, const glm::vec3& p, float grow) {
  e.lo = glm::min(e.lo, p - glm::vec3(grow));
  e.hi = glm::max(e.hi, p + glm::vec3(grow));
  e.sum += p;
  ++e.count;
}

// Skeleton points of a primitive, a Coons patch, or the spline a SplineOfNodes places its copies on.
NodeExtent primitiveExtent(const BlobNode& n, double t, const Affine& m) {
  NodeExtent e;
  bool geometric = n.type <= NodeType::Capsule || n.type == NodeType::CoonsPatch || n.type == NodeType::SplineOfNodes;
  if (!geometric) return e;
  const auto& specs = nodeTypeInfo(n.type).params;
  int r = paramIndex(n.type, "radius");
  float grow = r >= 0 ? std::max(0.0f, std::get<FloatTrack>(n.params[size_t(r)]).evaluate(t)) * m.scale() : 0.0f;
  for (size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].kind == ParamKind::Vec3 && !isDirection(specs[i].name) && !isColorParam(specs[i]))
      addPoint(e, m.apply(std::get<Vec3Track>(n.params[i]).evaluate(t)), grow);
    else if (specs[i].kind == ParamKind::Vec3List)
      for (const auto& p : std::get<ControlPoints>(n.params[i])) addPoint(e, m.apply(p.evaluate(t)), grow);
  }
  return e;
}

Affine frameOf(const BlobNode& n, double t, const Affine& parent) {
  glm::mat3 R = glm::mat3_cast(glm::normalize(n.quatParam("rotation").evaluate(t)));
  glm::vec3 s = n.vec3Param("scale").evaluate(t);
  glm::mat3 S(1.0f);
  S[0][0] = s.x;
  S[1][1] = s.y;
  S[2][2] = s.z;
  Affine local{R * S, n.vec3Param("translation").evaluate(t)};
  return Affine{parent.linear * local.linear, parent.apply(local.origin)};
}

NodeExtent visit(const BlobNode& n, double t, const Affine& m, std::unordered_map<int, NodeExtent>* out) {
  NodeExtent e = primitiveExtent(n, t, m);
  Affine inner = n.type == NodeType::Frame ? frameOf(n, t, m) : m;
  // The child of a SplineOfNodes lives in each copy's local frame: its copies are where the spline is.
  for (const BlobNode& c : n.children) {
    NodeExtent ce = visit(c, t, inner, out);
    if (n.type != NodeType::SplineOfNodes) e.merge(ce);
  }
  if (out) (*out)[n.id] = e;
  return e;
}

void visitPreorder(const BlobNode& n, double t, const Affine& m, bool inRootChain, std::vector<NodeExtent>& out) {
  const size_t me = out.size();
  out.emplace_back(primitiveExtent(n, t, m));
  const bool stillChain = inRootChain && isTransparentLink(n);
  Affine inner = n.type == NodeType::Frame && !inRootChain ? frameOf(n, t, m) : m;
  NodeExtent e = out[me];
  for (const BlobNode& c : n.children) {
    const size_t slot = out.size();
    visitPreorder(c, t, inner, stillChain, out);
    if (n.type != NodeType::SplineOfNodes) {
      e.merge(out[slot]);
    } else if (e.count > 0 && out[slot].count > 0) {
      // The copies of the child along the spline: its box grows by the (largest) copy's.
      const float scale = std::max(n.floatParam("scaleStart").evaluate(t), n.floatParam("scaleEnd").evaluate(t));
      const glm::vec3 half = 0.5f * out[slot].size() * scale;  // the child is in the spline's space
      e.lo -= half;
      e.hi += half;
    }
  }
  out[me] = e;
}

}  // namespace

bool isTransparentLink(const BlobNode& n) {
  if (n.children.size() != 1) return false;
  return (n.type >= NodeType::Frame && n.type <= NodeType::Bend) || n.type == NodeType::Blend ||
         n.type == NodeType::Union || n.type == NodeType::HyperBlend;
}

void extentsInsideRootChain(const BlobTree& tree, double timeSec, std::vector<NodeExtent>& out) {
  out.clear();
  out.reserve(tree.root.subtreeSize());
  visitPreorder(tree.root, timeSec, Affine{}, true, out);
}

NodeExtent subtreeExtent(const BlobNode& n, double timeSec) { return visit(n, timeSec, Affine{}, nullptr); }

std::unordered_map<int, NodeExtent> worldExtents(const BlobTree& tree, double timeSec) {
  std::unordered_map<int, NodeExtent> out;
  visit(tree.root, timeSec, Affine{}, &out);
  return out;
}

}  // namespace animorph
