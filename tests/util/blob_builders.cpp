#include "util/blob_builders.h"

#include <glm/gtc/quaternion.hpp>

namespace animorph::test {

BlobNode pointNode(int id, glm::vec3 center, float radius, float intensity, float stiffness) {
  BlobNode n = makeBlobNode(NodeType::Point, id);
  n.vec3Param("center") = Vec3Track(center);
  n.floatParam("radius") = FloatTrack(radius);
  n.floatParam("intensity") = FloatTrack(intensity);
  n.floatParam("stiffness") = FloatTrack(stiffness);
  return n;
}

BlobNode segmentNode(int id, glm::vec3 a, glm::vec3 b, float radius) {
  BlobNode n = makeBlobNode(NodeType::Segment, id);
  n.vec3Param("a") = Vec3Track(a);
  n.vec3Param("b") = Vec3Track(b);
  n.floatParam("radius") = FloatTrack(radius);
  return n;
}

BlobNode convSegmentNode(int id, glm::vec3 a, glm::vec3 b, float radius, float sharpness) {
  BlobNode n = makeBlobNode(NodeType::ConvSegment, id);
  n.vec3Param("a") = Vec3Track(a);
  n.vec3Param("b") = Vec3Track(b);
  n.floatParam("radius") = FloatTrack(radius);
  n.floatParam("sharpness") = FloatTrack(sharpness);
  return n;
}

BlobNode triangleNode(int id, glm::vec3 a, glm::vec3 b, glm::vec3 c, float radius) {
  BlobNode n = makeBlobNode(NodeType::Triangle, id);
  n.vec3Param("a") = Vec3Track(a);
  n.vec3Param("b") = Vec3Track(b);
  n.vec3Param("c") = Vec3Track(c);
  n.floatParam("radius") = FloatTrack(radius);
  return n;
}

BlobNode circleNode(int id, glm::vec3 center, glm::vec3 normal, float circleRadius, float radius) {
  BlobNode n = makeBlobNode(NodeType::Circle, id);
  n.vec3Param("center") = Vec3Track(center);
  n.vec3Param("normal") = Vec3Track(normal);
  n.floatParam("skeletonRadius") = FloatTrack(circleRadius);
  n.floatParam("radius") = FloatTrack(radius);
  return n;
}

BlobNode operatorNode(NodeType type, int id, std::vector<BlobNode> children) {
  BlobNode n = makeBlobNode(type, id);
  n.children = std::move(children);
  return n;
}

BlobTree treeOf(BlobNode root, float threshold) {
  BlobTree t;
  t.threshold = FloatTrack(threshold);
  t.root = std::move(root);
  return t;
}

namespace {

glm::vec3 rv(std::mt19937& rng, float s = 0.4f) {
  std::uniform_real_distribution<float> u(-s, s);
  return {u(rng), u(rng), u(rng)};
}

float rf(std::mt19937& rng, float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); }

// Gives every float / vec3 parameter a second key so tracks are exercised.
void animate(BlobNode& n, std::mt19937& rng) {
  const auto& specs = nodeTypeInfo(n.type).params;
  for (size_t i = 0; i < specs.size(); ++i) {
    if (isColorParam(specs[i])) continue;  // colours stay at the default (the random trees stay as they were)
    if (auto* f = std::get_if<FloatTrack>(&n.params[i])) {
      float v = f->evaluate(0.0);
      f->setKey(1.0, v * rf(rng, 0.8f, 1.2f));
    } else if (auto* v = std::get_if<Vec3Track>(&n.params[i])) {
      glm::vec3 x = v->evaluate(0.0);
      v->setKey(1.0, x + rv(rng, 0.05f));
    }
  }
}

BlobNode randomPrimitive(std::mt19937& rng, int& id) {
  static const NodeType kinds[] = {NodeType::Point,    NodeType::Sphere, NodeType::Segment,  NodeType::Cylinder,
                                   NodeType::Cone,     NodeType::Disc,   NodeType::Circle,   NodeType::Triangle,
                                   NodeType::Curve,    NodeType::ConvSegment, NodeType::Capsule};
  NodeType t = kinds[std::uniform_int_distribution<int>(0, 10)(rng)];
  BlobNode n = makeBlobNode(t, id++);
  const auto& specs = nodeTypeInfo(t).params;
  for (size_t i = 0; i < specs.size(); ++i) {
    const ParamSpec& p = specs[i];
    std::string name = p.name;
    if (isColorParam(p)) continue;
    if (p.kind == ParamKind::Vec3) {
      if (name == "normal") n.params[i] = Vec3Track(glm::normalize(rv(rng) + glm::vec3(0, 0.5f, 0)));
      else n.params[i] = Vec3Track(rv(rng));
    } else if (p.kind == ParamKind::Vec3List) {
      ControlPoints pts;
      for (int k = 0; k < 3; ++k) pts.push_back(Vec3Track(rv(rng)));
      n.params[i] = pts;
    } else if (p.kind == ParamKind::Float) {
      if (name == "radius") n.params[i] = FloatTrack(t == NodeType::ConvSegment || t == NodeType::Capsule ? rf(rng, 0.05f, 0.15f) : rf(rng, 0.2f, 0.45f));
      else if (name == "intensity") n.params[i] = FloatTrack(rf(rng, 0.7f, 1.3f));
      else if (name == "stiffness") n.params[i] = FloatTrack(rf(rng, 0.0f, 1.0f) < 0.5f ? 3.0f : 2.0f);
      else if (name == "sharpness") n.params[i] = FloatTrack(rf(rng, 4.0f, 12.0f));
      else n.params[i] = FloatTrack(rf(rng, 0.05f, 0.15f));  // skeleton radii
    }
  }
  animate(n, rng);
  return n;
}

}  // namespace

BlobNode randomNode(std::mt19937& rng, int depth, int& id) {
  int choice = depth <= 0 ? 0 : std::uniform_int_distribution<int>(0, 13)(rng);
  if (choice <= 3) return randomPrimitive(rng, id);
  static const NodeType ops[] = {NodeType::Blend,        NodeType::HyperBlend,   NodeType::Union,
                                 NodeType::Intersection, NodeType::Difference,   NodeType::RUnion,
                                 NodeType::RIntersection, NodeType::BoundedBlend, NodeType::Frame,
                                 NodeType::Twist,        NodeType::Taper,        NodeType::Bend,
                                 NodeType::SplineOfNodes, NodeType::CoonsPatch};
  NodeType t = ops[std::uniform_int_distribution<int>(0, 13)(rng)];
  BlobNode n = makeBlobNode(t, id++);
  const NodeTypeInfo& info = nodeTypeInfo(t);
  int nc = info.minChildren;
  if (info.maxChildren < 0 || info.maxChildren > nc) nc += std::uniform_int_distribution<int>(0, 2)(rng);
  if (info.maxChildren >= 0) nc = std::min(nc, info.maxChildren);
  for (int i = 0; i < nc; ++i) n.children.push_back(randomNode(rng, depth - 1, id));
  switch (t) {
    case NodeType::HyperBlend: n.floatParam("q") = FloatTrack(rf(rng, 1.0f, 4.0f)); break;
    case NodeType::BoundedBlend:
      n.floatParam("a0") = FloatTrack(rf(rng, 0.2f, 1.0f));
      n.floatParam("a3") = FloatTrack(rf(rng, 0.2f, 1.0f));
      break;
    case NodeType::Frame:
      n.vec3Param("translation") = Vec3Track(rv(rng, 0.2f));
      n.quatParam("rotation") = QuatTrack(glm::angleAxis(rf(rng, -2.0f, 2.0f), glm::normalize(rv(rng) + glm::vec3(0.1f))));
      n.vec3Param("scale") = Vec3Track(glm::vec3(rf(rng, 0.7f, 1.3f), rf(rng, 0.7f, 1.3f), rf(rng, 0.7f, 1.3f)));
      break;
    case NodeType::Twist:
      n.vec3Param("a") = Vec3Track(glm::vec3(0, -0.5f, 0));
      n.vec3Param("b") = Vec3Track(glm::vec3(0, 0.5f, 0) + rv(rng, 0.1f));
      n.floatParam("angle") = FloatTrack(rf(rng, -2.0f, 2.0f));
      break;
    case NodeType::Taper:
      n.vec3Param("a") = Vec3Track(glm::vec3(0, -0.5f, 0));
      n.vec3Param("b") = Vec3Track(glm::vec3(0, 0.5f, 0));
      n.floatParam("scaleA") = FloatTrack(rf(rng, 0.6f, 1.4f));
      n.floatParam("scaleB") = FloatTrack(rf(rng, 0.6f, 1.4f));
      break;
    case NodeType::Bend:
      n.vec3Param("a") = Vec3Track(glm::vec3(0, -0.5f, 0));
      n.vec3Param("b") = Vec3Track(glm::vec3(0, 0.5f, 0));
      n.floatParam("angle") = FloatTrack(rf(rng, -1.0f, 1.0f));
      n.vec3Param("direction") = Vec3Track(glm::vec3(1, 0, 0));
      break;
    case NodeType::SplineOfNodes: {
      ControlPoints pts;
      for (int k = 0; k < 3; ++k) pts.push_back(Vec3Track(rv(rng, 0.3f)));
      n.pointsParam("points") = pts;
      n.floatParam("count") = FloatTrack(3.0f);
      n.floatParam("scaleEnd") = FloatTrack(0.6f);
      break;
    }
    case NodeType::CoonsPatch: {
      n.children.clear();
      auto curve = [&](glm::vec3 a, glm::vec3 b) {
        ControlPoints c;
        c.push_back(Vec3Track(a));
        c.push_back(Vec3Track(0.5f * (a + b) + rv(rng, 0.1f)));
        c.push_back(Vec3Track(b));
        return c;
      };
      glm::vec3 p00(-0.3f, 0, -0.3f), p10(0.3f, 0, -0.3f), p01(-0.3f, 0, 0.3f), p11(0.3f, 0.1f, 0.3f);
      n.pointsParam("bottom") = curve(p00, p10);
      n.pointsParam("top") = curve(p01, p11);
      n.pointsParam("left") = curve(p00, p01);
      n.pointsParam("right") = curve(p10, p11);
      n.floatParam("resolution") = FloatTrack(2.0f);
      n.floatParam("radius") = FloatTrack(0.2f);
      break;
    }
    default: break;
  }
  return n;
}

}  // namespace animorph::test
