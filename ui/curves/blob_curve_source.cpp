// The curve editor's source for a BlobTree node: its animated parameters
// over the tree's time, shown in frames.
#include "ui/curves/curve_source.h"

#include "ui/common/blob_time.h"
#include "core/blobtree/tree_edit.h"
#include "core/doc/blobtree_commands.h"

namespace animorph {

namespace {

class BlobCurveSource final : public CurveSource {
 public:
  BlobCurveSource(const Document& doc, const Actor& actor, const BlobNode& node)
      : doc_(doc), actorId_(actor.id), node_(node.id) {}

  std::string id() const override { return "blob/" + actorId_ + "/" + std::to_string(node_); }
  std::string title() const override {
    const BlobNode* n = node();
    if (!n) return {};
    return n->name.empty() ? nodeTypeInfo(n->type).name : n->name;
  }
  std::string emptyHint() const override {
    return "No animated parameters. Key one in the inspector (diamond buttons).";
  }

  std::vector<CurveChannel> channels() const override {
    std::vector<CurveChannel> out;
    const BlobTree* tree = this->tree();
    const BlobNode* n = node();
    if (!tree || !n) return out;
    const auto& specs = nodeTypeInfo(n->type).params;
    static const char* kAxis[3] = {"x", "y", "z"};
    auto add = [&](ParamAddress a, const std::string& base, ParamKind kind) {
      if (!isAnimated(*tree, a)) return;
      int count = channelCount(kind);
      for (int c = 0; c < count; ++c)
        out.push_back({a, c, count == 1 ? base : base + "." + kAxis[c], kind == ParamKind::Quat, count == 1 ? -1 : c});
    };
    for (size_t i = 0; i < specs.size(); ++i) {
      if (specs[i].kind == ParamKind::Vec3List) {
        const auto& pts = std::get<ControlPoints>(n->params[i]);
        for (size_t k = 0; k < pts.size(); ++k)
          add({n->id, int(i), int(k)}, std::string(specs[i].name) + "[" + std::to_string(k) + "]", ParamKind::Vec3);
      } else {
        add({n->id, int(i), -1}, specs[i].name, specs[i].kind);
      }
    }
    return out;
  }

  CurveAxis axis() const override {
    const Timeline& tl = doc_.project().timeline;
    CurveAxis ax;
    ax.xPerTime = tl.fps > 0.0 ? tl.fps : 24.0;
    ax.label = "frame";
    ax.snapStep = 1.0;
    ax.snapLabel = "Snap to frames";
    ax.rangeStart = tl.frameStart;
    ax.rangeEnd = tl.frameEnd;
    if (const Actor* a = doc_.project().findActor(actorId_)) ax.playheads.push_back({blobTreeTimeNow(doc_, *a) * ax.xPerTime, "", false});
    return ax;
  }

  ConstTrackPtr track(const ParamAddress& a) const override {
    const BlobTree* t = tree();
    return t ? findTrack(*t, a) : ConstTrackPtr{};
  }
  ConstTrackPtr track(const std::any& snapshot, const ParamAddress& a) const override {
    const BlobTree* t = std::any_cast<BlobTree>(&snapshot);
    return t ? findTrack(*t, a) : ConstTrackPtr{};
  }
  std::any snapshot() const override {
    const BlobTree* t = tree();
    return t ? std::any(*t) : std::any();
  }

  Result<std::unique_ptr<Command>> edit(std::string label, const KeyEditFn& fn, std::string mergeKey,
                                        const std::any* from) const override {
    const BlobTree* start = from ? std::any_cast<BlobTree>(from) : tree();
    if (!start) return Error{"no BlobTree actor '" + actorId_ + "'"};
    BlobTree copy = *start;
    Status s = fn(blobTrackSet(copy));
    if (!s) return Error{"actor '" + actorId_ + "': " + s.error()};
    return setBlobTreeCommand(doc_.project(), actorId_, std::move(copy), std::move(label), std::move(mergeKey));
  }

 private:
  const BlobTree* tree() const {
    const Actor* a = doc_.project().findActor(actorId_);
    return a && a->kind == ActorKind::BlobTree ? &a->blobTree : nullptr;
  }
  const BlobNode* node() const {
    const BlobTree* t = tree();
    return t ? t->find(node_) : nullptr;
  }

  const Document& doc_;
  std::string actorId_;
  int node_;
};

}  // namespace

std::unique_ptr<CurveSource> makeBlobCurveSource(const Document& doc, const std::string& actorId, int node) {
  const Actor* a = doc.project().findActor(actorId);
  const BlobNode* n = a && a->kind == ActorKind::BlobTree ? a->blobTree.find(node) : nullptr;
  if (!n) return nullptr;
  return std::make_unique<BlobCurveSource>(doc, *a, *n);
}

std::unique_ptr<CurveSource> curveSourceForSelection(const Document& doc) {
  const Selection& sel = doc.selection;
  const MorphSetup& m = doc.project().morph;
  if (auto blob = makeBlobCurveSource(doc, sel.actorId, sel.node)) return blob;
  const bool morphActor = !sel.actorId.empty() && sel.node < 0 &&
                          (sel.actorId == m.sourceActorId || sel.actorId == m.targetActorId);
  const bool nothing = doc.project().findActor(sel.actorId) == nullptr;
  if (m.enabled() && (nothing || morphActor)) return makeMorphCurveSource(doc);
  return nullptr;
}

}  // namespace animorph
