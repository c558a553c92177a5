#include "core/blobtree/blob_tree.h"

#include <algorithm>
#include <cassert>

namespace animorph {

namespace {

template <class T, class N>
auto& paramAs(N& node, std::string_view name) {
  int i = paramIndex(node.type, name);
  assert(i >= 0 && "no such parameter for this node type");
  assert(std::holds_alternative<T>(node.params[size_t(i)]));
  return std::get<T>(node.params[size_t(i)]);
}

template <class N>
N* findIn(N& n, int id) {
  if (n.id == id) return &n;
  for (auto& c : n.children)
    if (N* r = findIn(c, id)) return r;
  return nullptr;
}

int maxId(const BlobNode& n) {
  int m = n.id;
  for (const auto& c : n.children) m = std::max(m, maxId(c));
  return m;
}

}  // namespace

FloatTrack& BlobNode::floatParam(std::string_view n) { return paramAs<FloatTrack>(*this, n); }
const FloatTrack& BlobNode::floatParam(std::string_view n) const { return paramAs<FloatTrack>(*this, n); }
Vec3Track& BlobNode::vec3Param(std::string_view n) { return paramAs<Vec3Track>(*this, n); }
const Vec3Track& BlobNode::vec3Param(std::string_view n) const { return paramAs<Vec3Track>(*this, n); }
QuatTrack& BlobNode::quatParam(std::string_view n) { return paramAs<QuatTrack>(*this, n); }
const QuatTrack& BlobNode::quatParam(std::string_view n) const { return paramAs<QuatTrack>(*this, n); }
ControlPoints& BlobNode::pointsParam(std::string_view n) { return paramAs<ControlPoints>(*this, n); }
const ControlPoints& BlobNode::pointsParam(std::string_view n) const { return paramAs<ControlPoints>(*this, n); }

size_t BlobNode::subtreeSize() const {
  size_t s = 1;
  for (const auto& c : children) s += c.subtreeSize();
  return s;
}

BlobNode makeBlobNode(NodeType type, int id, std::string name) {
  BlobNode n;
  n.id = id;
  n.type = type;
  n.name = std::move(name);
  for (const ParamSpec& p : nodeTypeInfo(type).params) {
    switch (p.kind) {
      case ParamKind::Float: n.params.emplace_back(FloatTrack(p.defaultValue.x)); break;
      case ParamKind::Vec3: n.params.emplace_back(Vec3Track(p.defaultValue)); break;
      case ParamKind::Quat: n.params.emplace_back(QuatTrack(glm::quat(1.0f, 0.0f, 0.0f, 0.0f))); break;
      case ParamKind::Vec3List: n.params.emplace_back(ControlPoints{}); break;
    }
  }
  return n;
}

BlobNode* BlobTree::find(int id) { return findIn(root, id); }
const BlobNode* BlobTree::find(int id) const { return findIn(root, id); }
int BlobTree::nextId() const { return maxId(root) + 1; }

}  // namespace animorph
