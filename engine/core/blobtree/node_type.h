#pragma once
// The BlobTree node types and their parameters (docs/design.md §3; docs/blobtree.md).
// One table describes every type: JSON name, children allowed, and each
// parameter's name, kind, default and constraint. Parsing, validation,
// serialisation and the editor's property panels all read it.
#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "core/math/color.h"

namespace animorph {

enum class NodeType : uint8_t {
  // skeletal primitives: g(d) = I (1 - (d/R)^2)^k of the distance to a skeleton
  Point, Sphere, Segment, Cylinder, Cone, Disc, Circle, Triangle, Curve,
  // other primitives
  ConvSegment,  // convolution segment, Cauchy kernel, surface radius -> weight
  Capsule,      // canal surface T * max(0, 2 - dist / R)
  // operators
  Blend, HyperBlend, Union, Intersection, Difference, RUnion, RIntersection, BoundedBlend,
  // space maps
  Frame, Twist, Taper, Bend,
  // meta-primitives
  SplineOfNodes, CoonsPatch,
};

enum class ParamKind : uint8_t { Float, Vec3, Quat, Vec3List };

enum class ParamRule : uint8_t {
  Any,
  NonNegative,   // floats >= 0 (radii, stiffness)
  Positive,      // floats > 0
  AtLeastOne,    // floats >= 1 (hyper-blend q, counts)
  NonZero,       // vectors with non-zero length; Frame scale: every component non-zero
  Color,         // vectors: an sRGB colour, every component in [0, 1]
};

// The colour every primitive has unless told otherwise (its "color" parameter's default): the
// clay tone BlobTree surfaces were drawn in before they carried colour (sRGB), so trees saved
// without colours look as they did.
inline constexpr glm::vec3 kDefaultBlobColor = kClayColorSrgb;

struct ParamSpec {
  const char* name;
  ParamKind kind;
  bool required;
  glm::vec3 defaultValue;  // Float: .x; Quat: identity; Vec3List: none (always required)
  ParamRule rule;
  const char* doc;
  int minCount = 0;        // Vec3List: minimum number of points
};

struct NodeTypeInfo {
  NodeType type;
  const char* name;         // JSON "type"
  const char* category;     // "primitive", "operator", "map", "meta"
  int minChildren;
  int maxChildren;          // -1: unbounded
  std::vector<ParamSpec> params;
  const char* doc;
};

// Description of a type (always valid).
const NodeTypeInfo& nodeTypeInfo(NodeType t);
// Type by JSON name; nullptr when unknown.
const NodeTypeInfo* findNodeType(std::string_view name);
// All types, in enum order.
const std::vector<NodeTypeInfo>& allNodeTypes();
// Index of a parameter in the type's spec list, or -1.
int paramIndex(NodeType t, std::string_view name);

// True for a colour parameter (ParamRule::Color): not a position, not moved by geometry edits.
inline bool isColorParam(const ParamSpec& p) { return p.rule == ParamRule::Color; }

// True for the skeletal-potential primitives (Point ... Curve).
inline bool isSkeletalType(NodeType t) { return t <= NodeType::Curve; }
// True for the operators (Blend ... BoundedBlend): nodes that combine their children's fields in
// the same space.
inline bool isOperatorType(NodeType t) { return t >= NodeType::Blend && t <= NodeType::BoundedBlend; }

}  // namespace animorph
