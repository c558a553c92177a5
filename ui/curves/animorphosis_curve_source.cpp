// The curve editor's source for the animorphosis: the global s(u) and, when a
// link with its own s(u) is selected in the correspondence editor, that one,
// over the animorphosis' progress u (0..1).
#include "ui/curves/curve_source.h"

#include "core/animorphosis/tree_index.h"
#include "core/doc/animorphosis_commands.h"
#include "core/project/animation_end_cache.h"
#include "core/project/animorphosis_project.h"

namespace animorph {

namespace {

constexpr int kGlobalSNode = 0, kLinkSNode = 1;  // ParamAddress::node of the two kinds of s tracks
constexpr int kLinkColor = 3;

// The s track at a in m (AnimorphosisSetup or const AnimorphosisSetup), or null.
template <class Setup>
auto findSTrack(Setup& m, const ParamAddress& a) -> decltype(&m.globalS) {
  if (a.node == kGlobalSNode && a.param == 0) return &m.globalS;
  if (a.node == kLinkSNode && a.param >= 0 && a.param < int(m.graph.links.size()) &&
      m.graph.links[size_t(a.param)].sOverride)
    return &*m.graph.links[size_t(a.param)].sOverride;
  return nullptr;
}

ConstTrackPtr constSTrack(const AnimorphosisSetup& m, const ParamAddress& a) {
  const FloatTrack* t = findSTrack(m, a);
  return t ? ConstTrackPtr(t) : ConstTrackPtr{};
}

class AnimorphosisCurveSource final : public CurveSource {
 public:
  AnimorphosisCurveSource(const Document& doc, int nodeA, int nodeB) : doc_(doc), nodeA_(nodeA), nodeB_(nodeB) {}

  std::string id() const override {
    return "animorphosis/" + std::to_string(nodeA_) + "-" + std::to_string(nodeB_);
  }
  std::string title() const override { return "Animorphosis s(u) (x: progress u)"; }
  std::string emptyHint() const override { return "No s curve."; }

  std::vector<CurveChannel> channels() const override {
    std::vector<CurveChannel> out;
    out.push_back({{kGlobalSNode, 0, -1}, 0, "Global s(u)", false, -1});
    const int i = linkIndex();
    if (i >= 0 && setup().graph.links[size_t(i)].sOverride)
      out.push_back({{kLinkSNode, i, -1}, 0, "s(u) of " + linkName(), false, kLinkColor});
    return out;
  }

  CurveAxis axis() const override {
    const Project& p = doc_.project();
    CurveAxis ax = progressAxis("u: progress of the animorphosis");
    const double t = p.timeline.currentTimeSec();
    AnimationEndScope ends(p, &doc_, doc_.revision());  // drawn every frame: the trees' ends are kept
    ax.playheads.push_back({animorphosisTiming(p).u(t), "u", false});
    return ax;
  }

  ConstTrackPtr track(const ParamAddress& a) const override { return constSTrack(setup(), a); }
  ConstTrackPtr track(const std::any& snapshot, const ParamAddress& a) const override {
    const AnimorphosisSetup* m = std::any_cast<AnimorphosisSetup>(&snapshot);
    return m ? constSTrack(*m, a) : ConstTrackPtr{};
  }
  std::any snapshot() const override { return setup(); }

  Result<std::unique_ptr<Command>> edit(std::string label, const KeyEditFn& fn, std::string mergeKey,
                                        const std::any* from) const override {
    const AnimorphosisSetup* start = from ? std::any_cast<AnimorphosisSetup>(from) : &setup();
    if (!start) return Error{"animorphosis: nothing to edit"};
    AnimorphosisSetup copy = *start;
    TrackSet set;
    set.find = [&copy](const ParamAddress& a) {
      FloatTrack* t = findSTrack(copy, a);
      return t ? TrackPtr(t) : TrackPtr{};
    };
    set.name = [this](const ParamAddress& a) {
      return a.node == kGlobalSNode ? std::string("animorphosis global s") : "animorphosis s of " + linkName();
    };
    set.minTimeSec = 0.0;
    set.maxTimeSec = 1.0;
    if (Status s = fn(set); !s) return Error{s.error()};
    Project trial = doc_.project();
    trial.animorphosis = copy;
    if (Status s = checkAnimorphosis(trial); !s) return Error{s.error()};
    return setAnimorphosisCommand(doc_.project(), std::move(copy), std::move(label), std::move(mergeKey));
  }

 private:
  const AnimorphosisSetup& setup() const { return doc_.project().animorphosis; }
  int linkIndex() const { return nodeA_ < 0 ? -1 : setup().graph.find(nodeA_, nodeB_); }
  std::string linkName() const {
    const Project& p = doc_.project();
    const Actor* a = p.findActor(setup().sourceActorId);
    const Actor* b = p.findActor(setup().targetActorId);
    const BlobNode* na = a ? a->blobTree.find(nodeA_) : nullptr;
    const BlobNode* nb = b ? b->blobTree.find(nodeB_) : nullptr;
    return (na ? nameOfNode(*na) : std::to_string(nodeA_)) + " -> " + (nb ? nameOfNode(*nb) : std::to_string(nodeB_));
  }

  const Document& doc_;
  int nodeA_, nodeB_;
};

}  // namespace

std::unique_ptr<CurveSource> makeAnimorphosisCurveSource(const Document& doc, int nodeA, int nodeB) {
  if (!doc.project().animorphosis.enabled()) return nullptr;
  return std::make_unique<AnimorphosisCurveSource>(doc, nodeA, nodeB);
}

}  // namespace animorph
