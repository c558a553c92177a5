#include "core/animorphosis/generic_tree.h"

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <unordered_map>

#include "core/animorphosis/tree_geometry.h"
#include "core/animorphosis/tree_index.h"
#include "core/animorphosis/validate_correspondence.h"

namespace animorph {

namespace {

constexpr int kSyntheticId = std::numeric_limits<int>::min();
constexpr size_t kMaxHyperBlendChildren = 64;

struct BuildError {
  std::string message;
};

// How a node combines its children's fields (maps sum them before mapping).
enum class Combine { Sum, Max, Min, Other };

Combine combineOf(NodeType t) {
  switch (t) {
    case NodeType::Blend:
    case NodeType::Frame:
    case NodeType::Twist:
    case NodeType::Taper:
    case NodeType::Bend: return Combine::Sum;
    case NodeType::Union: return Combine::Max;
    case NodeType::Intersection: return Combine::Min;
    default: return Combine::Other;
  }
}

bool isLeafType(NodeType t) { return t <= NodeType::Capsule || t == NodeType::CoonsPatch; }
bool isMap(NodeType t) { return t >= NodeType::Frame && t <= NodeType::Bend; }
bool isBridgeOp(NodeType t) { return t == NodeType::Blend || t == NodeType::Union || t == NodeType::HyperBlend; }
bool pairable(NodeType x, NodeType y) { return x == y || (isBridgeOp(x) && isBridgeOp(y)); }
// Operators whose children are told apart by their place.
bool ordered(NodeType t) {
  return t == NodeType::Difference || t == NodeType::RUnion || t == NodeType::RIntersection ||
         t == NodeType::BoundedBlend || t == NodeType::SplineOfNodes;
}
// A child of zero field leaves the node's field unchanged.
bool acceptsNull(NodeType t) {
  Combine c = combineOf(t);
  return c == Combine::Sum || c == Combine::Max || t == NodeType::HyperBlend;
}

const char* typeName(NodeType t) { return nodeTypeInfo(t).name; }

// Scaling every intensity by f scales the field by f.
bool scalable(const BlobNode& n) {
  if (isLeafType(n.type)) return paramIndex(n.type, "intensity") >= 0;
  if (combineOf(n.type) == Combine::Other && n.type != NodeType::HyperBlend && n.type != NodeType::SplineOfNodes)
    return false;
  return std::all_of(n.children.begin(), n.children.end(), scalable);
}

void scaleIntensity(BlobNode& n, float f) {
  if (int i = paramIndex(n.type, "intensity"); i >= 0)
    for (auto& k : std::get<FloatTrack>(n.params[size_t(i)]).keys()) {
      k.value *= f;
      k.d1 *= f;
      k.d2 *= f;
    }
  for (BlobNode& c : n.children) scaleIntensity(c, f);
}

// The track of the point a fraction f of the way from a to b, keyed where either is.
Vec3Track pointAlong(const Vec3Track& a, const Vec3Track& b, float f) {
  if (f <= 0.0f) return a;
  if (f >= 1.0f) return b;
  std::set<double> times;
  for (const auto& k : a.keys()) times.insert(k.timeSec);
  for (const auto& k : b.keys()) times.insert(k.timeSec);
  if (times.empty()) return a;
  const KeyInterp interp = a.keys().empty() ? KeyInterp::Hermite : a.keys().front().interp;
  Vec3Track r = a;
  r.clearKeys();
  for (double t : times) r.setKey(t, glm::mix(a.evaluate(t), b.evaluate(t), f), interp);
  return r;
}

// Piece `which` of a convolution segment cut at the fractions `cuts` (ascending, inside 0..1) of
// its length: the field of a convolution segment is its kernel integrated along it, so its pieces
// under a sum make the whole's field (exactly where the ends move linearly between keys).
BlobNode segmentPiece(const BlobNode& n, size_t which, const std::vector<float>& cuts) {
  BlobNode r = n;
  const float f0 = which == 0 ? 0.0f : cuts[which - 1], f1 = which < cuts.size() ? cuts[which] : 1.0f;
  r.vec3Param("a") = pointAlong(n.vec3Param("a"), n.vec3Param("b"), f0);
  r.vec3Param("b") = pointAlong(n.vec3Param("a"), n.vec3Param("b"), f1);
  return r;
}

BlobNode shallow(const BlobNode& n) {
  BlobNode s;
  s.id = n.id;
  s.name = n.name;
  s.type = n.type;
  s.params = n.params;
  return s;
}

// The identity of `like`'s kind, keeping its axes; false for kinds without one.
bool identityOf(const BlobNode& like, BlobNode& out) {
  out = makeBlobNode(like.type, kSyntheticId);
  switch (like.type) {
    case NodeType::Blend:
    case NodeType::Union:
    case NodeType::Intersection:
    case NodeType::Frame: return true;
    case NodeType::HyperBlend: out.floatParam("q") = like.floatParam("q"); return true;
    case NodeType::Twist:
    case NodeType::Taper:
      out.vec3Param("a") = like.vec3Param("a");
      out.vec3Param("b") = like.vec3Param("b");
      return true;
    case NodeType::Bend:
      out.vec3Param("a") = like.vec3Param("a");
      out.vec3Param("b") = like.vec3Param("b");
      out.vec3Param("direction") = like.vec3Param("direction");
      return true;
    default: return false;
  }
}

// Point ⊂ sphere, and point ⊂ segment ⊂ cylinder ⊂ cone: the simplest kind that holds both (a point
// is a ball of radius 0 or a segment of length 0, a segment a cylinder of radius 0, a cylinder a cone
// of equal radii; a ball is none of the axial kinds: a cylinder of length 0 is a flat disc). False
// when no kind holds both.
bool commonSkeleton(NodeType x, NodeType y, NodeType& out) {
  auto any = [&](NodeType t) { return x == t || y == t; };
  auto axial = [](NodeType t) {
    return t == NodeType::Point || t == NodeType::Segment || t == NodeType::Cylinder || t == NodeType::Cone;
  };
  if (any(NodeType::Sphere)) {
    out = NodeType::Sphere;
    return (x == NodeType::Sphere || x == NodeType::Point) && (y == NodeType::Sphere || y == NodeType::Point);
  }
  if (!axial(x) || !axial(y)) return false;
  out = any(NodeType::Cone)       ? NodeType::Cone
        : any(NodeType::Cylinder) ? NodeType::Cylinder
        : any(NodeType::Segment)  ? NodeType::Segment
                                  : NodeType::Point;
  return true;
}

// n rewritten as the same skeleton of the wider kind `to` (commonSkeleton's chains).
BlobNode generalised(const BlobNode& n, NodeType to) {
  if (n.type == to) return n;
  BlobNode g = makeBlobNode(to, n.id, n.name);
  for (const char* p : {"radius", "intensity", "stiffness"}) g.floatParam(p) = n.floatParam(p);
  bool pointLike = n.type == NodeType::Point || n.type == NodeType::Sphere;
  const Vec3Track& a = pointLike ? n.vec3Param("center") : n.vec3Param("a");
  const Vec3Track& b = pointLike ? n.vec3Param("center") : n.vec3Param("b");
  FloatTrack r0 = n.type == NodeType::Sphere || n.type == NodeType::Cylinder ? n.floatParam("skeletonRadius")
                  : n.type == NodeType::Cone                                  ? n.floatParam("radiusA")
                                                                              : FloatTrack(0.0f);
  FloatTrack r1 = n.type == NodeType::Cone ? n.floatParam("radiusB") : r0;
  if (to == NodeType::Sphere) {
    g.vec3Param("center") = a;
    g.floatParam("skeletonRadius") = r0;
    return g;
  }
  g.vec3Param("a") = a;
  g.vec3Param("b") = b;
  if (to == NodeType::Cylinder) g.floatParam("skeletonRadius") = r0;
  if (to == NodeType::Cone) {
    g.floatParam("radiusA") = r0;
    g.floatParam("radiusB") = r1;
  }
  return g;
}

struct Builder {
  const CorrespondenceGraph& g;
  TreeIndex ia, ib;
  GenericOptions opt;
  GenericTree& out;
  std::unordered_map<int, int> curveOfLink;

  using EndDests = std::unordered_map<int, std::vector<int>>;
  using DestMemo = std::unordered_map<const BlobNode*, std::vector<int>>;

  static const char* sideName(MorphSide s) { return s == MorphSide::A ? "source" : "target"; }
  static MorphSide other(MorphSide s) { return s == MorphSide::A ? MorphSide::B : MorphSide::A; }

  std::string describe(const BlobNode& n, MorphSide s) const {
    if (n.id == kSyntheticId) return std::string("an inserted ") + typeName(n.type) + " of the " + sideName(s);
    return std::string(sideName(s)) + " " + nameOfNode(n) + " (" + typeName(n.type) + ")";
  }
  std::string describeLink(int li) const {
    const auto& l = g.links[size_t(li)];
    return "source " + nameOfNode(ia.node(l.nodeA)) + " -> target " + nameOfNode(ib.node(l.nodeB));
  }

  int curveFor(int link, int inherited) {
    const auto& l = g.links[size_t(link)];
    if (!l.sOverride) return inherited;
    auto [it, added] = curveOfLink.try_emplace(link, int(out.sCurves.size()));
    if (added) out.sCurves.push_back(*l.sOverride);
    return it->second;
  }

  static int end(const CorrespondenceLink& l, MorphSide s) { return s == MorphSide::A ? l.nodeA : l.nodeB; }

  // id -> index of the kid whose sub-tree holds it.
  static std::unordered_map<int, int> owners(const std::vector<BlobNode>& kids) {
    std::unordered_map<int, int> m;
    std::vector<std::pair<const BlobNode*, int>> stack;
    for (size_t i = 0; i < kids.size(); ++i) stack.push_back({&kids[i], int(i)});
    while (!stack.empty()) {
      auto [n, i] = stack.back();
      stack.pop_back();
      if (n->id != kSyntheticId) m[n->id] = i;
      for (const BlobNode& c : n->children) stack.push_back({&c, i});
    }
    return m;
  }

  static const std::vector<int>& dests(const BlobNode& n, const EndDests& ends, DestMemo& memo) {
    if (auto it = memo.find(&n); it != memo.end()) return it->second;
    std::vector<int> d;
    if (auto e = ends.find(n.id); e != ends.end()) d = e->second;
    for (const BlobNode& c : n.children) {
      const auto& cd = dests(c, ends, memo);
      d.insert(d.end(), cd.begin(), cd.end());
    }
    std::sort(d.begin(), d.end());
    d.erase(std::unique(d.begin(), d.end()), d.end());
    return memo[&n] = std::move(d);
  }

  // The piece of convolution segment n that goes with partner j of d (indices in partners, the
  // other parent's children): the partners' centroids at time 0 projected on the segment order the
  // pieces, cut half way between neighbours (a segment split in two or three on the other side
  // morphs piece by piece into its parts).
  static BlobNode convSegmentShare(const BlobNode& n, int j, const std::vector<int>& d,
                                   const std::vector<BlobNode>& partners) {
    const glm::vec3 a = n.vec3Param("a").evaluate(0.0), ab = n.vec3Param("b").evaluate(0.0) - a;
    const float len2 = glm::dot(ab, ab);
    std::vector<std::pair<float, int>> along;
    for (int k : d) {
      const glm::vec3 c = subtreeExtent(partners[size_t(k)], 0.0).centroid();
      along.push_back({len2 > 0.0f ? std::clamp(glm::dot(c - a, ab) / len2, 0.0f, 1.0f) : 0.0f, k});
    }
    std::sort(along.begin(), along.end());
    std::vector<float> cuts;
    size_t which = 0;
    for (size_t i = 0; i < along.size(); ++i) {
      if (along[i].second == j) which = i;
      if (i > 0) cuts.push_back(std::max(cuts.empty() ? 0.0f : cuts.back(), 0.5f * (along[i - 1].first + along[i].first)));
    }
    return segmentPiece(n, which, cuts);
  }

  // The part of n that goes with partner j when n's links go to several partners (partners: the
  // other parent's children, which j indexes).
  BlobNode restrictTo(const BlobNode& n, int j, Combine parent, MorphSide side, const EndDests& ends,
                      DestMemo& memo, const std::vector<BlobNode>& partners) {
    const std::vector<int> d = dests(n, ends, memo);
    if (d.size() == 1) return n;
    BlobNode r = shallow(n);
    float share = 1.0f / float(d.size());
    std::string count = std::to_string(d.size());
    if (isLeafType(n.type)) {
      if (parent == Combine::Sum) {
        if (n.type == NodeType::ConvSegment) return convSegmentShare(n, j, d, partners);
        if (paramIndex(n.type, "intensity") < 0)
          throw BuildError{describe(n, side) + " links to " + count + " separate sub-trees of the " +
                           sideName(other(side)) + " but has no intensity to share among its copies under a sum"};
        scaleIntensity(r, share);
      } else if (parent == Combine::Other) {
        throw BuildError{describe(n, side) + " links to " + count + " separate sub-trees of the " +
                         sideName(other(side)) + " but its parent's operator would change if it were split"};
      }
      return r;
    }
    Combine own = combineOf(n.type);
    if (own == Combine::Other || own != parent) {
      // Its children cannot be shared out; whole copies still keep the field: under a union or an
      // intersection as they are, under a sum each at 1/k of the intensity. In copy j, the parts
      // linked to other partners are unlinked and shrink.
      if (parent == Combine::Max || parent == Combine::Min) return n;
      if (parent == Combine::Sum && scalable(n)) {
        r = n;
        scaleIntensity(r, share);
        return r;
      }
      throw BuildError{describe(n, side) + " would be split into " + count + " copies, one per partner in the " +
                       sideName(other(side)) + ", but its operator does not distribute over its parent's and "
                       "its sub-tree cannot be scaled; link the node itself to one partner, or link its parent"};
    }
    for (const BlobNode& c : n.children) {
      const auto& cd = dests(c, ends, memo);
      if (cd.empty()) {
        if (own != Combine::Sum) {
          r.children.push_back(c);  // max / min of equal copies is the copy
        } else if (scalable(c)) {
          r.children.push_back(c);
          scaleIntensity(r.children.back(), share);
        } else if (j == d.front()) {
          r.children.push_back(c);
        }
      } else if (std::binary_search(cd.begin(), cd.end(), j)) {
        if (cd.size() > 1 && j == cd.front()) out.splitCopies += int(cd.size()) - 1;
        r.children.push_back(restrictTo(c, j, own, side, ends, memo, partners));
      }
    }
    return r;
  }

  // A zero-field copy of n: zero intensities (convolution segments and
  // capsules: zero radius), identity warps, and with `collapse` every
  // skeleton point at `anchor`.
  BlobNode nullOf(const BlobNode& n, const glm::vec3& anchor, bool collapse, MorphSide side) const {
    BlobNode r;
    if (isLeafType(n.type) || n.type == NodeType::SplineOfNodes) {
      r = shallow(n);
      r.id = kSyntheticId;
      const auto& specs = nodeTypeInfo(n.type).params;
      bool radiusIsSize = n.type == NodeType::ConvSegment || n.type == NodeType::Capsule;
      for (size_t i = 0; i < specs.size(); ++i) {
        std::string_view name = specs[i].name;
        if (name == "intensity" || (radiusIsSize && name == "radius")) {
          r.params[i] = FloatTrack(0.0f);
        } else if (collapse && specs[i].kind == ParamKind::Vec3 && name != "normal" && !isColorParam(specs[i])) {
          r.params[i] = Vec3Track(anchor);
        } else if (collapse && specs[i].kind == ParamKind::Vec3List) {
          for (auto& p : std::get<ControlPoints>(r.params[i])) p = Vec3Track(anchor);
        } else if (collapse && (name == "skeletonRadius" || name == "radiusA" || name == "radiusB")) {
          r.params[i] = FloatTrack(0.0f);
        }
      }
    } else if (n.type == NodeType::Difference) {
      r = makeBlobNode(NodeType::Difference, kSyntheticId);
    } else if (!identityOf(n, r)) {
      throw BuildError{describe(n, side) + " has no partner, and a zero-intensity copy of a " + typeName(n.type) +
                       " is not empty: link it to a node of the " + sideName(other(side))};
    }
    glm::vec3 childAnchor = n.type == NodeType::SplineOfNodes ? glm::vec3(0.0f) : anchor;
    for (const BlobNode& c : n.children) r.children.push_back(nullOf(c, childAnchor, collapse, side));
    return r;
  }

  GenericNode zip(const BlobNode& real, const BlobNode& null, MorphSide side, int sCurve) const {
    GenericNode z;
    z.a = shallow(side == MorphSide::A ? real : null);
    z.b = shallow(side == MorphSide::A ? null : real);
    z.sCurve = sCurve;
    (side == MorphSide::A ? z.sourceA : z.sourceB) = real.id == kSyntheticId ? -1 : real.id;
    for (size_t k = 0; k < real.children.size(); ++k)
      z.children.push_back(zip(real.children[k], null.children[k], side, sCurve));
    return z;
  }

  GenericNode nullPair(const BlobNode& real, MorphSide side, const glm::vec3& anchor, bool collapse, int sCurve) {
    ++out.nullPartners;
    return zip(real, nullOf(real, anchor, collapse, side), side, sCurve);
  }

  static std::vector<int> linksWithout(const std::vector<int>& links, const std::vector<CorrespondenceLink>& all,
                                       int idA, int idB) {
    std::vector<int> r;
    for (int li : links)
      if (all[size_t(li)].nodeA != idA && all[size_t(li)].nodeB != idB) r.push_back(li);
    return r;
  }

  BlobNode wrapInIdentityOf(const BlobNode& like, const BlobNode& inner, MorphSide likeSide) {
    BlobNode w;
    if (!identityOf(like, w))
      throw BuildError{describe(like, likeSide) + " lies on the path to a link but a " + typeName(like.type) +
                       " has no identity to pair it with in the " + sideName(other(likeSide)) +
                       "; link it, or link the nodes below it differently"};
    w.children.push_back(inner);
    return w;
  }

  // Pairs two nodes known to correspond; links: those strictly inside both.
  std::vector<GenericNode> pairNodes(const BlobNode& A, const BlobNode& B, const std::vector<int>& links,
                                     int sCurve) {
    if (NodeType common; A.type != B.type && commonSkeleton(A.type, B.type, common))
      return pairNodes(generalised(A, common), generalised(B, common), links, sCurve);
    if (pairable(A.type, B.type)) {
      GenericNode n;
      n.a = shallow(A);
      n.b = shallow(B);
      n.sCurve = sCurve;
      n.sourceA = A.id == kSyntheticId ? -1 : A.id;
      n.sourceB = B.id == kSyntheticId ? -1 : B.id;
      if (!isLeafType(A.type)) n.children = pairChildren(A, B, links, sCurve);
      if (A.type != B.type && n.children.size() > kMaxHyperBlendChildren)
        throw BuildError{describe(A, MorphSide::A) + " and " + describe(B, MorphSide::B) +
                         " are bridged through a hyper-blend, which takes at most 64 children (here " +
                         std::to_string(n.children.size()) + ")"};
      return {std::move(n)};
    }
    if (isMap(A.type) && isMap(B.type)) {
      BlobNode idA, idB;
      identityOf(A, idA);
      identityOf(B, idB);
      GenericNode inner;
      inner.a = idA;
      inner.b = shallow(B);
      inner.sCurve = sCurve;
      inner.sourceB = B.id == kSyntheticId ? -1 : B.id;
      inner.children = pairChildren(A, B, links, sCurve);
      GenericNode outer;
      outer.a = shallow(A);
      outer.b = idA;
      outer.sCurve = sCurve;
      outer.sourceA = A.id == kSyntheticId ? -1 : A.id;
      outer.children.push_back(std::move(inner));
      return {std::move(outer)};
    }
    if (isMap(B.type)) return pairNodes(wrapInIdentityOf(B, A, MorphSide::B), B, links, sCurve);
    if (isMap(A.type)) return pairNodes(A, wrapInIdentityOf(A, B, MorphSide::A), links, sCurve);
    if (!links.empty())
      throw BuildError{describe(A, MorphSide::A) + " and " + describe(B, MorphSide::B) +
                       " are of kinds that cannot be morphed into each other, and links below them (" +
                       describeLink(links.front()) + ") need a common structure; link their parents or "
                       "children instead"};
    // Kinds that do not meet: one shrinks to zero intensity where it is, the other grows where it will be.
    std::vector<GenericNode> r;
    r.push_back(nullPair(A, MorphSide::A, glm::vec3(0.0f), false, sCurve));
    r.push_back(nullPair(B, MorphSide::B, glm::vec3(0.0f), false, sCurve));
    return r;
  }

  // Pairs an A child (or its copy) with a B child whose sub-trees share `links`.
  std::vector<GenericNode> pairEdge(const BlobNode& A, const BlobNode& B, const std::vector<int>& links,
                                    int sCurve) {
    int direct = -1;
    bool aLinked = false, bLinked = false;
    for (int li : links) {
      const auto& l = g.links[size_t(li)];
      if (l.nodeA == A.id && l.nodeB == B.id) direct = li;
      aLinked = aLinked || l.nodeA == A.id;
      bLinked = bLinked || l.nodeB == B.id;
    }
    if (direct >= 0) return pairNodes(A, B, linksWithout(links, g.links, A.id, B.id), curveFor(direct, sCurve));
    if (aLinked && bLinked)
      throw BuildError{describe(A, MorphSide::A) + " and " + describe(B, MorphSide::B) +
                       " are each linked inside the other's sub-tree (crossing links)"};
    if (aLinked) return pairNodes(wrapInIdentityOf(B, A, MorphSide::B), B, links, sCurve);
    if (bLinked) return pairNodes(A, wrapInIdentityOf(A, B, MorphSide::A), links, sCurve);
    if (pairable(A.type, B.type)) return pairNodes(A, B, links, sCurve);
    BlobNode w;
    if (identityOf(B, w)) return pairNodes(wrapInIdentityOf(B, A, MorphSide::B), B, links, sCurve);
    return pairNodes(A, wrapInIdentityOf(A, B, MorphSide::A), links, sCurve);
  }

  std::vector<GenericNode> pairInOrder(const BlobNode& pa, const BlobNode& pb, const std::vector<int>& links,
                                       int sCurve) {
    if (pa.type != pb.type || pa.children.size() != pb.children.size())
      throw BuildError{describe(pa, MorphSide::A) + " and " + describe(pb, MorphSide::B) +
                       " correspond, and a " + typeName(ordered(pa.type) ? pa.type : pb.type) +
                       " pairs its children by their place: both need the same kind and number of children"};
    auto aOwner = owners(pa.children), bOwner = owners(pb.children);
    std::vector<std::vector<int>> per(pa.children.size());
    for (int li : links) {
      int i = aOwner.at(g.links[size_t(li)].nodeA), j = bOwner.at(g.links[size_t(li)].nodeB);
      if (i != j)
        throw BuildError{"link " + describeLink(li) + " is refused: it joins child " + std::to_string(i + 1) +
                         " of " + describe(pa, MorphSide::A) + " to child " + std::to_string(j + 1) + " of " +
                         describe(pb, MorphSide::B) + ", whose children pair by their place"};
      per[size_t(i)].push_back(li);
    }
    std::vector<GenericNode> r;
    for (size_t k = 0; k < pa.children.size(); ++k) {
      auto nodes = pairEdge(pa.children[k], pb.children[k], per[k], sCurve);
      if (nodes.size() != 1)
        throw BuildError{describe(pa.children[k], MorphSide::A) + " and " + describe(pb.children[k], MorphSide::B) +
                         " sit at the same place under a " + typeName(pa.type) +
                         " but cannot be morphed into each other"};
      r.push_back(std::move(nodes.front()));
    }
    return r;
  }

  glm::vec3 centroidOf(const std::vector<const BlobNode*>& nodes, double t) const {
    NodeExtent e;
    for (const BlobNode* n : nodes) e.merge(subtreeExtent(*n, t));
    return e.centroid();
  }

  std::vector<GenericNode> pairChildren(const BlobNode& pa, const BlobNode& pb, const std::vector<int>& links,
                                        int sCurve) {
    if (ordered(pa.type) || ordered(pb.type)) return pairInOrder(pa, pb, links, sCurve);
    const auto& aKids = pa.children;
    const auto& bKids = pb.children;
    auto aOwner = owners(aKids), bOwner = owners(bKids);
    EndDests aEnds, bEnds;
    std::set<std::pair<int, int>> edges;
    std::map<std::pair<int, int>, std::vector<int>> edgeLinks;
    for (int li : links) {
      const auto& l = g.links[size_t(li)];
      int i = aOwner.at(l.nodeA), j = bOwner.at(l.nodeB);
      aEnds[l.nodeA].push_back(j);
      bEnds[l.nodeB].push_back(i);
      edges.insert({i, j});
      edgeLinks[{i, j}].push_back(li);
    }
    DestMemo aMemo, bMemo;
    // copies[i][j]: the part of A kid i that goes with B kid j (and the same for B).
    std::vector<std::map<int, BlobNode>> aCopies(aKids.size()), bCopies(bKids.size());
    auto makeCopies = [&](const std::vector<BlobNode>& kids, MorphSide side, const EndDests& ends, DestMemo& memo,
                          Combine parent, std::vector<std::map<int, BlobNode>>& copies,
                          const std::vector<BlobNode>& partners) {
      for (size_t i = 0; i < kids.size(); ++i) {
        std::vector<int> d = dests(kids[i], ends, memo);
        for (int j : d) copies[i].emplace(j, restrictTo(kids[i], j, parent, side, ends, memo, partners));
        if (d.size() > 1) out.splitCopies += int(d.size()) - 1;
      }
    };
    makeCopies(aKids, MorphSide::A, aEnds, aMemo, combineOf(pa.type), aCopies, bKids);
    makeCopies(bKids, MorphSide::B, bEnds, bMemo, combineOf(pb.type), bCopies, aKids);

    std::vector<GenericNode> r;
    for (const auto& [i, j] : edges) {
      auto nodes = pairEdge(aCopies[size_t(i)].at(j), bCopies[size_t(j)].at(i), edgeLinks[{i, j}], sCurve);
      if (nodes.size() > 1 && !(acceptsNull(pa.type) && acceptsNull(pb.type)))
        throw BuildError{describe(aKids[size_t(i)], MorphSide::A) + " and " + describe(bKids[size_t(j)], MorphSide::B) +
                         " are of kinds that cannot be morphed into each other, and their parents cannot hold one "
                         "shrinking while the other grows"};
      for (auto& n : nodes) r.push_back(std::move(n));
    }
    addNullPartners(pa, pb, aCopies, bCopies, MorphSide::A, sCurve, r);
    addNullPartners(pb, pa, bCopies, aCopies, MorphSide::B, sCurve, r);
    return r;
  }

  // Unlinked children of `own` get a zero partner under `partner`, at the partner of their nearest linked sibling.
  void addNullPartners(const BlobNode& own, const BlobNode& partner, const std::vector<std::map<int, BlobNode>>& ownCopies,
                       const std::vector<std::map<int, BlobNode>>& partnerCopies, MorphSide side, int sCurve,
                       std::vector<GenericNode>& r) {
    double tOwn = side == MorphSide::A ? opt.anchorTimeSecA : opt.anchorTimeSecB;
    double tPartner = side == MorphSide::A ? opt.anchorTimeSecB : opt.anchorTimeSecA;
    std::vector<glm::vec3> centre(own.children.size());
    for (size_t i = 0; i < own.children.size(); ++i) centre[i] = subtreeExtent(own.children[i], tOwn).centroid();
    for (size_t i = 0; i < own.children.size(); ++i) {
      if (!ownCopies[i].empty()) continue;
      if (!acceptsNull(partner.type))
        throw BuildError{describe(own.children[i], side) + " has no partner, and its partner parent " +
                         describe(partner, other(side)) + " cannot take a zero child; link it"};
      int nearest = -1;
      float best = std::numeric_limits<float>::max();
      for (size_t k = 0; k < own.children.size(); ++k) {
        if (ownCopies[k].empty()) continue;
        float d = glm::distance(centre[k], centre[i]);
        if (d < best) best = d, nearest = int(k);
      }
      glm::vec3 anchor;
      if (nearest >= 0) {
        int j = ownCopies[size_t(nearest)].begin()->first;
        anchor = subtreeExtent(partnerCopies[size_t(j)].at(nearest), tPartner).centroid();
      } else {
        std::vector<const BlobNode*> all;
        for (const BlobNode& c : partner.children) all.push_back(&c);
        anchor = centroidOf(all, tPartner);
      }
      r.push_back(nullPair(own.children[i], side, anchor, true, sCurve));
    }
  }
};

size_t countNodes(const GenericNode& n) {
  size_t s = 1;
  for (const auto& c : n.children) s += countNodes(c);
  return s;
}

BlobNode sideNode(const GenericNode& g, MorphSide side, int& nextId) {
  BlobNode n = side == MorphSide::A ? g.a : g.b;
  n.id = nextId++;
  n.children.reserve(g.children.size());
  for (const auto& c : g.children) n.children.push_back(sideNode(c, side, nextId));
  return n;
}

}  // namespace

size_t GenericTree::size() const { return countNodes(root); }

Result<GenericTree> buildGenericTree(const BlobTree& a, const BlobTree& b, const CorrespondenceGraph& graph,
                                     const GenericOptions& options) {
  Status valid = validateCorrespondence(a, b, graph);
  if (!valid) return Error{valid.error()};
  GenericTree c;
  c.thresholdA = a.threshold;
  c.thresholdB = b.threshold;
  Builder builder{graph, TreeIndex(a), TreeIndex(b), options, c, {}};
  try {
    int rootLink = graph.find(a.root.id, b.root.id);
    int sCurve = rootLink >= 0 ? builder.curveFor(rootLink, -1) : -1;
    std::vector<int> links;
    for (size_t i = 0; i < graph.links.size(); ++i)
      if (int(i) != rootLink) links.push_back(int(i));
    auto nodes = builder.pairNodes(a.root, b.root, links, sCurve);
    if (nodes.size() == 1) {
      c.root = std::move(nodes.front());
    } else {
      c.root.a = makeBlobNode(NodeType::Blend, 0);
      c.root.b = makeBlobNode(NodeType::Blend, 0);
      c.root.sCurve = sCurve;
      c.root.children = std::move(nodes);
    }
  } catch (const BuildError& e) {
    return Error{"cannot build the generic tree: " + e.message};
  }
  return c;
}

BlobTree genericSide(const GenericTree& c, MorphSide side) {
  BlobTree t;
  t.threshold = side == MorphSide::A ? c.thresholdA : c.thresholdB;
  int next = 1;
  t.root = sideNode(c.root, side, next);
  return t;
}

}  // namespace animorph
