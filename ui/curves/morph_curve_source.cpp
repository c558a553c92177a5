// The curve editor's source for the morph: easing (over a transition's
// progress), blend w(u), noise amplitude and the keyed stand-in segment
// tracks (over the morph's progress), all on a normalised x axis 0..1.
#include "ui/curves/curve_source.h"

#include "core/doc/morph_tracks.h"

namespace animorph {

namespace {

// Colours of the morph's single-channel tracks (indices into the panel's palette).
constexpr int kBlendColor = 3, kNoiseColor = 4, kRadiusColor = 5;

class MorphCurveSource final : public CurveSource {
 public:
  explicit MorphCurveSource(const Document& doc) : doc_(doc) {}

  std::string id() const override { return "morph"; }
  std::string title() const override { return "Morph tracks (x: progress u)"; }
  std::string emptyHint() const override { return "The morph has no tracks."; }

  std::vector<CurveChannel> channels() const override {
    std::vector<CurveChannel> out;
    static const char* kAxis[3] = {"x", "y", "z"};
    for (const ParamAddress& a : morphTrackAddresses(doc_.project().morph)) {
      if (a.node == kMorphTracksNode) {
        static const char* kNames[3] = {"Easing (transition u)", "Blend w(u)", "Noise amplitude"};
        static const int kColors[3] = {-1, kBlendColor, kNoiseColor};
        out.push_back({a, 0, kNames[a.param], false, kColors[a.param]});
        continue;
      }
      std::string base = std::string(a.node == int(MorphSlot::Source) ? "Source" : "Target") + " seg " +
                         std::to_string(a.point) + " ";
      if (a.param == int(SegmentChannel::RadiusScale)) {
        out.push_back({a, 0, base + "radius scale", false, kRadiusColor});
      } else {
        const char* which = a.param == int(SegmentChannel::AOffset) ? "A offset." : "B offset.";
        for (int c = 0; c < 3; ++c) out.push_back({a, c, base + which + kAxis[c], false, c});
      }
    }
    return out;
  }

  CurveAxis axis() const override {
    const MorphSetup& m = doc_.project().morph;
    const double frame = doc_.project().timeline.currentFrame;
    CurveAxis ax = progressAxis("u: progress (easing over A->B / C->D, the rest over B->C)");
    ax.playheads.push_back({morphProgressAt(m, frame), "morph u", false});
    const double tu = transitionProgressAt(m, frame);
    if (tu >= 0.0) ax.playheads.push_back({tu, frame < m.markers.b ? "collapse u" : "expand u", true});
    return ax;
  }

  ConstTrackPtr track(const ParamAddress& a) const override { return findMorphTrack(doc_.project().morph, a); }
  ConstTrackPtr track(const std::any& snapshot, const ParamAddress& a) const override {
    const MorphSetup* m = std::any_cast<MorphSetup>(&snapshot);
    return m ? findMorphTrack(*m, a) : ConstTrackPtr{};
  }
  std::any snapshot() const override { return doc_.project().morph; }

  Result<std::unique_ptr<Command>> edit(std::string label, const KeyEditFn& fn, std::string mergeKey,
                                        const std::any* from) const override {
    const MorphSetup* start = from ? std::any_cast<MorphSetup>(from) : nullptr;
    return editMorphTracks(
        doc_.project(), std::move(label), [&](MorphSetup& m) { return fn(morphTrackSet(m)); }, std::move(mergeKey),
        start);
  }

 private:
  const Document& doc_;
};

}  // namespace

CurveAxis progressAxis(std::string label) {
  CurveAxis ax;
  ax.xPerTime = 1.0;
  ax.label = std::move(label);
  ax.snapStep = 0.01;
  ax.snapLabel = "Snap to 0.01";
  ax.rangeStart = 0.0;
  ax.rangeEnd = 1.0;
  return ax;
}

std::unique_ptr<CurveSource> makeMorphCurveSource(const Document& doc) {
  if (!doc.project().morph.enabled()) return nullptr;
  return std::make_unique<MorphCurveSource>(doc);
}

}  // namespace animorph
