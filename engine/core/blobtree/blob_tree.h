#pragma once
// The animated BlobTree (docs/design.md §3): nodes with stable integer ids and
// names, children, and every parameter a Track. Plain data: evaluating it at
// a time is done by compileFieldProgram (blobtree/compile.h).
#include <string>
#include <variant>
#include <vector>

#include "core/anim/track.h"
#include "core/blobtree/node_type.h"

namespace animorph {

using ControlPoints = std::vector<Vec3Track>;
using ParamValue = std::variant<FloatTrack, Vec3Track, QuatTrack, ControlPoints>;

struct BlobNode {
  int id = 0;          // stable and unique in the tree (the correspondence graph refers to it)
  std::string name;
  NodeType type = NodeType::Blend;
  std::vector<ParamValue> params;  // one per nodeTypeInfo(type).params entry, same order
  std::vector<BlobNode> children;

  // Typed access by name; the parameter must exist with that kind (asserted).
  FloatTrack& floatParam(std::string_view name);
  const FloatTrack& floatParam(std::string_view name) const;
  Vec3Track& vec3Param(std::string_view name);
  const Vec3Track& vec3Param(std::string_view name) const;
  QuatTrack& quatParam(std::string_view name);
  const QuatTrack& quatParam(std::string_view name) const;
  ControlPoints& pointsParam(std::string_view name);
  const ControlPoints& pointsParam(std::string_view name) const;

  // Number of nodes in this subtree, itself included.
  size_t subtreeSize() const;
  bool operator==(const BlobNode&) const = default;
};

// A node of `type` with every parameter at its default (required ones at 0 / empty).
BlobNode makeBlobNode(NodeType type, int id, std::string name = {});

struct BlobTree {
  FloatTrack threshold{1.0f};  // T(t), > 0
  BlobNode root;

  // Node with this id, or nullptr.
  BlobNode* find(int id);
  const BlobNode* find(int id) const;
  // One more than the largest id in use.
  int nextId() const;
  bool operator==(const BlobTree&) const = default;
};

}  // namespace animorph
