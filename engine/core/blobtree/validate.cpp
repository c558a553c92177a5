#include "core/blobtree/validate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace animorph {

std::string describeNode(const BlobNode& n) {
  std::string s = "node " + std::to_string(n.id);
  if (!n.name.empty()) s += " '" + n.name + "'";
  s += " (" + std::string(nodeTypeInfo(n.type).name) + ")";
  return s;
}

namespace {

std::string num(float v) {
  if (std::isnan(v)) return "NaN";
  std::ostringstream o;
  o << v;
  return o.str();
}

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Status checkFloat(const BlobNode& n, const ParamSpec& p, const FloatTrack& t) {
  for (size_t k = 0; k < t.keys().size(); ++k) {
    const auto& key = t.keys()[k];
    float v = key.value;
    std::string at = " at key " + std::to_string(k);
    std::string where = describeNode(n) + ": parameter '" + p.name + "'";
    if (!std::isfinite(v) || !std::isfinite(key.d1) || !std::isfinite(key.d2) || !std::isfinite(key.timeSec))
      return Error{where + " is not a finite number (" + num(v) + at + ")"};
    switch (p.rule) {
      case ParamRule::NonNegative:
        if (v < 0.0f) return Error{where + " is negative (" + num(v) + at + ")"};
        break;
      case ParamRule::Positive:
        if (v <= 0.0f) return Error{where + " must be > 0 (" + num(v) + at + ")"};
        break;
      case ParamRule::AtLeastOne:
        if (v < 1.0f) return Error{where + " must be >= 1 (" + num(v) + at + ")"};
        break;
      default: break;
    }
  }
  return Status::success();
}

Status checkVec3(const BlobNode& n, const ParamSpec& p, const Vec3Track& t) {
  for (size_t k = 0; k < t.keys().size(); ++k) {
    const auto& key = t.keys()[k];
    std::string where = describeNode(n) + ": parameter '" + p.name + "'";
    std::string at = " at key " + std::to_string(k);
    if (!finite3(key.value) || !finite3(key.d1) || !finite3(key.d2) || !std::isfinite(key.timeSec))
      return Error{where + " has a non-finite component" + at};
    if (p.rule == ParamRule::Color) {
      for (int c = 0; c < 3; ++c)
        if (key.value[c] < 0.0f || key.value[c] > 1.0f)
          return Error{where + " has a colour component outside 0..1 (" + num(key.value[c]) + at + ")"};
    }
    if (p.rule == ParamRule::NonZero) {
      bool scale = n.type == NodeType::Frame;
      if (scale ? (key.value.x == 0.0f || key.value.y == 0.0f || key.value.z == 0.0f)
                : glm::length(key.value) < 1e-9f)
        return Error{where + (scale ? " has a zero component" : " has zero length") + at};
    }
  }
  return Status::success();
}

Status checkQuat(const BlobNode& n, const ParamSpec& p, const QuatTrack& t) {
  for (size_t k = 0; k < t.keys().size(); ++k) {
    const glm::quat& q = t.keys()[k].value;
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.w) ||
        glm::dot(q, q) < 1e-12f)
      return Error{describeNode(n) + ": parameter '" + p.name + "' is not a valid rotation at key " +
                   std::to_string(k)};
  }
  return Status::success();
}

}  // namespace

Status validateBlobNode(const BlobNode& n, std::vector<int>& ids) {
  if (size_t(n.type) >= allNodeTypes().size()) return Error{"node " + std::to_string(n.id) + ": unknown node type"};
  const NodeTypeInfo& info = nodeTypeInfo(n.type);
  if (std::find(ids.begin(), ids.end(), n.id) != ids.end())
    return Error{describeNode(n) + ": id " + std::to_string(n.id) + " is used by another node"};
  ids.push_back(n.id);
  if (n.params.size() != info.params.size())
    return Error{describeNode(n) + ": has " + std::to_string(n.params.size()) + " parameters, expected " +
                 std::to_string(info.params.size())};
  for (size_t i = 0; i < info.params.size(); ++i) {
    const ParamSpec& p = info.params[i];
    const ParamValue& v = n.params[i];
    Status s;
    switch (p.kind) {
      case ParamKind::Float:
        if (!std::holds_alternative<FloatTrack>(v)) return Error{describeNode(n) + ": parameter '" + p.name + "' must be a number track"};
        s = checkFloat(n, p, std::get<FloatTrack>(v));
        break;
      case ParamKind::Vec3:
        if (!std::holds_alternative<Vec3Track>(v)) return Error{describeNode(n) + ": parameter '" + p.name + "' must be a vector track"};
        s = checkVec3(n, p, std::get<Vec3Track>(v));
        break;
      case ParamKind::Quat:
        if (!std::holds_alternative<QuatTrack>(v)) return Error{describeNode(n) + ": parameter '" + p.name + "' must be a quaternion track"};
        s = checkQuat(n, p, std::get<QuatTrack>(v));
        break;
      case ParamKind::Vec3List: {
        if (!std::holds_alternative<ControlPoints>(v)) return Error{describeNode(n) + ": parameter '" + p.name + "' must be a list of points"};
        const auto& pts = std::get<ControlPoints>(v);
        if (int(pts.size()) < p.minCount)
          return Error{describeNode(n) + ": parameter '" + p.name + "' needs at least " + std::to_string(p.minCount) +
                       " points, has " + std::to_string(pts.size())};
        for (const auto& t : pts)
          if (!(s = checkVec3(n, p, t))) break;
        break;
      }
    }
    if (!s) return s;
  }
  int c = int(n.children.size());
  if (c < info.minChildren || (info.maxChildren >= 0 && c > info.maxChildren)) {
    std::string want = info.minChildren == info.maxChildren ? std::to_string(info.minChildren)
                       : info.maxChildren < 0 ? "at least " + std::to_string(info.minChildren)
                                              : std::to_string(info.minChildren) + " to " + std::to_string(info.maxChildren);
    return Error{describeNode(n) + ": has " + std::to_string(c) + " children, needs " + want};
  }
  for (const auto& ch : n.children)
    if (Status s = validateBlobNode(ch, ids); !s) return s;
  return Status::success();
}

Status validateBlobTree(const BlobTree& tree) {
  for (size_t k = 0; k < tree.threshold.keys().size(); ++k) {
    float v = tree.threshold.keys()[k].value;
    if (!std::isfinite(v) || v <= 0.0f)
      return Error{"threshold must be a finite number > 0 (" + num(v) + " at key " + std::to_string(k) + ")"};
  }
  std::vector<int> ids;
  return validateBlobNode(tree.root, ids);
}

}  // namespace animorph
