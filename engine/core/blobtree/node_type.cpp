#include "core/blobtree/node_type.h"

namespace animorph {

namespace {

using K = ParamKind;
using R = ParamRule;
const glm::vec3 z0(0.0f);

// Every primitive's colour (a Vec3 track of sRGB components in [0, 1]; docs/blobtree.md, "Colour").
ParamSpec colorParam() {
  return {"color", K::Vec3, false, kDefaultBlobColor, R::Color, "surface colour (sRGB, each component 0..1)", 0};
}

ParamSpec req(const char* n, K k, R r, const char* doc, int minCount = 0) {
  return {n, k, true, z0, r, doc, minCount};
}
ParamSpec opt(const char* n, K k, glm::vec3 d, R r, const char* doc) { return {n, k, false, d, r, doc, 0}; }
ParamSpec optf(const char* n, float d, R r, const char* doc) { return {n, K::Float, false, glm::vec3(d), r, doc, 0}; }

std::vector<ParamSpec> potential(std::vector<ParamSpec> shape) {
  shape.push_back(req("radius", K::Float, R::NonNegative, "radius of influence R (m)"));
  shape.push_back(optf("intensity", 1.0f, R::Any, "intensity I (potential at the skeleton)"));
  shape.push_back(optf("stiffness", 3.0f, R::NonNegative, "stiffness k of (1 - (d/R)^2)^k"));
  shape.push_back(colorParam());
  return shape;
}

std::vector<NodeTypeInfo> makeTable() {
  std::vector<NodeTypeInfo> t;
  t.push_back({NodeType::Point, "point", "primitive", 0, 0,
               potential({req("center", K::Vec3, R::Any, "the point")}), "potential around a point"});
  t.push_back({NodeType::Sphere, "sphere", "primitive", 0, 0,
               potential({req("center", K::Vec3, R::Any, "centre"),
                          req("skeletonRadius", K::Float, R::NonNegative, "radius of the solid ball skeleton")}),
               "potential around a solid ball"});
  t.push_back({NodeType::Segment, "segment", "primitive", 0, 0,
               potential({req("a", K::Vec3, R::Any, "start"), req("b", K::Vec3, R::Any, "end")}),
               "potential around a line segment"});
  t.push_back({NodeType::Cylinder, "cylinder", "primitive", 0, 0,
               potential({req("a", K::Vec3, R::Any, "axis start"), req("b", K::Vec3, R::Any, "axis end"),
                          req("skeletonRadius", K::Float, R::NonNegative, "radius of the solid cylinder")}),
               "potential around a solid capped cylinder"});
  t.push_back({NodeType::Cone, "cone", "primitive", 0, 0,
               potential({req("a", K::Vec3, R::Any, "axis start"), req("b", K::Vec3, R::Any, "axis end"),
                          req("radiusA", K::Float, R::NonNegative, "skeleton radius at a"),
                          req("radiusB", K::Float, R::NonNegative, "skeleton radius at b")}),
               "potential around a solid cone frustum"});
  t.push_back({NodeType::Disc, "disc", "primitive", 0, 0,
               potential({req("center", K::Vec3, R::Any, "centre"),
                          opt("normal", K::Vec3, {0, 1, 0}, R::NonZero, "disc normal"),
                          req("skeletonRadius", K::Float, R::NonNegative, "disc radius")}),
               "potential around a flat disc"});
  t.push_back({NodeType::Circle, "circle", "primitive", 0, 0,
               potential({req("center", K::Vec3, R::Any, "centre"),
                          opt("normal", K::Vec3, {0, 1, 0}, R::NonZero, "circle normal"),
                          req("skeletonRadius", K::Float, R::NonNegative, "circle radius")}),
               "potential around a circle (a torus)"});
  t.push_back({NodeType::Triangle, "triangle", "primitive", 0, 0,
               potential({req("a", K::Vec3, R::Any, "corner"), req("b", K::Vec3, R::Any, "corner"),
                          req("c", K::Vec3, R::Any, "corner")}),
               "potential around a triangle"});
  t.push_back({NodeType::Curve, "curve", "primitive", 0, 0,
               potential({req("points", K::Vec3List, R::Any, "Catmull-Rom control points (>= 2)", 2)}),
               "potential around a spline curve through the points"});
  t.push_back({NodeType::ConvSegment, "convSegment", "primitive", 0, 0,
               {req("a", K::Vec3, R::Any, "start"), req("b", K::Vec3, R::Any, "end"),
                req("radius", K::Float, R::NonNegative, "surface radius of a long segment (weight is derived)"),
                optf("sharpness", 10.0f, R::Positive, "Cauchy kernel S (1/m)"), colorParam()},
               "convolution segment (Cauchy kernel, closed form)"});
  t.push_back({NodeType::Capsule, "capsule", "primitive", 0, 0,
               {req("a", K::Vec3, R::Any, "start"), req("b", K::Vec3, R::Any, "end"),
                req("radius", K::Float, R::NonNegative, "capsule radius"), colorParam()},
               "canal surface: potential T * max(0, 2 - dist / radius)"});
  t.push_back({NodeType::Blend, "blend", "operator", 1, -1, {}, "sum of the children"});
  t.push_back({NodeType::HyperBlend, "hyperBlend", "operator", 1, 64,
               {optf("q", 2.0f, R::AtLeastOne, "exponent q >= 1 (1: blend; large: union)")},
               "(sum p_i^q)^(1/q)"});
  t.push_back({NodeType::Union, "union", "operator", 1, -1, {}, "max of the children"});
  t.push_back({NodeType::Intersection, "intersection", "operator", 1, -1, {}, "min of the children"});
  t.push_back({NodeType::Difference, "difference", "operator", 2, -1, {},
               "first child minus the union of the others: min(p1, 2T - max(rest))"});
  t.push_back({NodeType::RUnion, "rUnion", "operator", 2, 2, {}, "R-function union on s = p - T"});
  t.push_back({NodeType::RIntersection, "rIntersection", "operator", 2, 2, {}, "R-function intersection"});
  t.push_back({NodeType::BoundedBlend, "boundedBlend", "operator", 3, 3,
               {optf("a0", 1.0f, R::Any, "displacement amplitude"), optf("a1", 1.0f, R::Positive, "f1 scale"),
                optf("a2", 1.0f, R::Positive, "f2 scale"), optf("a3", 1.0f, R::Positive, "bounding solid scale")},
               "Pasko bounded blending of children 1 and 2 inside child 3"});
  t.push_back({NodeType::Frame, "frame", "map", 1, -1,
               {opt("translation", K::Vec3, z0, R::Any, "translation"),
                opt("rotation", K::Quat, z0, R::Any, "rotation quaternion [x, y, z, w] (slerp)"),
                opt("scale", K::Vec3, {1, 1, 1}, R::NonZero, "scale (components non-zero)")},
               "affine frame T * R * S over the blend of the children"});
  t.push_back({NodeType::Twist, "twist", "map", 1, -1,
               {req("a", K::Vec3, R::Any, "axis start"), req("b", K::Vec3, R::Any, "axis end"),
                optf("angle", 0.0f, R::Any, "twist angle from a to b (rad)")},
               "Barr twist about the axis a -> b"});
  t.push_back({NodeType::Taper, "taper", "map", 1, -1,
               {req("a", K::Vec3, R::Any, "axis start"), req("b", K::Vec3, R::Any, "axis end"),
                optf("scaleA", 1.0f, R::Positive, "cross-section scale at a"),
                optf("scaleB", 1.0f, R::Positive, "cross-section scale at b")},
               "Barr taper along the axis a -> b"});
  t.push_back({NodeType::Bend, "bend", "map", 1, -1,
               {req("a", K::Vec3, R::Any, "axis start"), req("b", K::Vec3, R::Any, "axis end"),
                optf("angle", 0.0f, R::Any, "bend angle over a -> b (rad)"),
                opt("direction", K::Vec3, {0, 1, 0}, R::NonZero, "direction the axis bends towards")},
               "Barr bend of the axis a -> b"});
  t.push_back({NodeType::SplineOfNodes, "splineOfNodes", "meta", 1, 1,
               {req("points", K::Vec3List, R::Any, "Catmull-Rom control points (>= 2)", 2),
                optf("count", 5.0f, R::AtLeastOne, "number of copies (rounded, <= 1000)"),
                optf("scaleStart", 1.0f, R::Positive, "scale of the first copy"),
                optf("scaleEnd", 1.0f, R::Positive, "scale of the last copy")},
               "copies of the child along a spline (blended), +Z turned along the tangent"});
  t.push_back({NodeType::CoonsPatch, "coonsPatch", "meta", 0, 0,
               potential({req("bottom", K::Vec3List, R::Any, "boundary curve v = 0 (>= 2 points)", 2),
                          req("top", K::Vec3List, R::Any, "boundary curve v = 1", 2),
                          req("left", K::Vec3List, R::Any, "boundary curve u = 0", 2),
                          req("right", K::Vec3List, R::Any, "boundary curve u = 1", 2),
                          optf("resolution", 4.0f, R::AtLeastOne, "cells per side (rounded, <= 64)")}),
               "bilinear Coons patch of the four curves: union of triangle primitives"});
  return t;
}

}  // namespace

const std::vector<NodeTypeInfo>& allNodeTypes() {
  static const std::vector<NodeTypeInfo> table = makeTable();
  return table;
}

const NodeTypeInfo& nodeTypeInfo(NodeType t) { return allNodeTypes()[size_t(t)]; }

const NodeTypeInfo* findNodeType(std::string_view name) {
  for (const auto& i : allNodeTypes())
    if (name == i.name) return &i;
  return nullptr;
}

int paramIndex(NodeType t, std::string_view name) {
  // The parameter names of each type as string_views, measured once: the compiler looks parameters
  // up by name for every node of every frame.
  static const std::vector<std::vector<std::string_view>> names = [] {
    std::vector<std::vector<std::string_view>> r;
    for (const NodeTypeInfo& info : allNodeTypes()) {
      r.emplace_back();
      for (const ParamSpec& p : info.params) r.back().emplace_back(p.name);
    }
    return r;
  }();
  const std::vector<std::string_view>& ps = names[size_t(t)];
  for (size_t i = 0; i < ps.size(); ++i)
    if (name == ps[i]) return int(i);
  return -1;
}

}  // namespace animorph
