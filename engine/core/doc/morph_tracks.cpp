#include "core/doc/morph_tracks.h"

#include <algorithm>
#include <cmath>

#include "core/standin_morph/transition.h"

namespace animorph {

namespace {

class MorphTracksCommand final : public Command {
 public:
  MorphTracksCommand(const MorphSetup& before, const MorphSetup& after, std::string label, std::string mergeKey)
      : before_(tracksOf(before)), after_(tracksOf(after)), label_(std::move(label)), mergeKey_(std::move(mergeKey)) {}
  void apply(Project& p) override { put(after_, p.morph); }
  void revert(Project& p) override { put(before_, p.morph); }
  std::string label() const override { return label_; }
  std::string mergeKey() const override { return mergeKey_; }
  bool mergeWith(const Command& other) override {
    auto* o = dynamic_cast<const MorphTracksCommand*>(&other);
    if (!o || mergeKey_.empty() || o->mergeKey_ != mergeKey_) return false;
    after_ = o->after_;
    return true;
  }

 private:
  // The animated part of a morph: only this is swapped in and out.
  struct Tracks {
    FloatTrack easing, blend, noiseAmplitude;
    std::vector<std::pair<std::string, std::vector<SegmentTracks>>> segments;  // by actor id
  };
  static Tracks tracksOf(const MorphSetup& m) {
    Tracks t{m.easing, m.blend, m.noiseAmplitude, {}};
    for (const ActorMorph& a : m.actors) t.segments.emplace_back(a.actorId, a.segmentTracks);
    return t;
  }
  static void put(const Tracks& t, MorphSetup& m) {
    m.easing = t.easing;
    m.blend = t.blend;
    m.noiseAmplitude = t.noiseAmplitude;
    for (const auto& [id, segs] : t.segments)
      if (ActorMorph* a = m.findActor(id)) a->segmentTracks = segs;
  }
  Tracks before_, after_;
  std::string label_;
  std::string mergeKey_;
};

const char* kSegmentChannelNames[3] = {"A offset", "B offset", "radius scale"};

template <class M, class Out>
Out trackIn(M& m, const ParamAddress& a) {
  if (a.node == kMorphTracksNode) {
    switch (a.param) {
      case int(MorphTrack::Easing): return Out{&m.easing};
      case int(MorphTrack::Blend): return Out{&m.blend};
      case int(MorphTrack::NoiseAmplitude): return Out{&m.noiseAmplitude};
      default: return Out{};
    }
  }
  if (a.node != int(MorphSlot::Source) && a.node != int(MorphSlot::Target)) return Out{};
  auto* am = slotActor(m, MorphSlot(a.node));
  auto* st = am ? findSegmentTracks(*am, a.point) : nullptr;
  if (!st) return Out{};
  switch (a.param) {
    case int(SegmentChannel::AOffset): return Out{&st->aOffset};
    case int(SegmentChannel::BOffset): return Out{&st->bOffset};
    case int(SegmentChannel::RadiusScale): return Out{&st->radiusScale};
    default: return Out{};
  }
}

const char* slotName(MorphSlot s) { return s == MorphSlot::Source ? "source" : "target"; }

// A neutral track over the morph: value v at u = 0 and u = 1.
template <class T>
Track<T> neutralTrack(const T& v) {
  Track<T> t;
  t.clearKeys();
  t.setKey(0.0, v);
  t.setKey(1.0, v);
  return t;
}

}  // namespace

ParamAddress morphTrackAddress(MorphTrack t) { return {kMorphTracksNode, int(t), -1}; }

ParamAddress segmentTrackAddress(MorphSlot slot, int segment, SegmentChannel c) {
  return {int(slot), int(c), segment};
}

bool overTransition(const ParamAddress& a) {
  return a.node == kMorphTracksNode && a.param == int(MorphTrack::Easing);
}

ActorMorph* slotActor(MorphSetup& m, MorphSlot slot) {
  return m.findActor(slot == MorphSlot::Source ? m.sourceActorId : m.targetActorId);
}
const ActorMorph* slotActor(const MorphSetup& m, MorphSlot slot) {
  return m.findActor(slot == MorphSlot::Source ? m.sourceActorId : m.targetActorId);
}

SegmentTracks* findSegmentTracks(ActorMorph& a, int segment) {
  for (auto& t : a.segmentTracks)
    if (t.segment == segment) return &t;
  return nullptr;
}
const SegmentTracks* findSegmentTracks(const ActorMorph& a, int segment) {
  for (const auto& t : a.segmentTracks)
    if (t.segment == segment) return &t;
  return nullptr;
}

TrackPtr findMorphTrack(MorphSetup& m, const ParamAddress& a) { return trackIn<MorphSetup, TrackPtr>(m, a); }
ConstTrackPtr findMorphTrack(const MorphSetup& m, const ParamAddress& a) {
  return trackIn<const MorphSetup, ConstTrackPtr>(m, a);
}

std::string morphTrackName(const ParamAddress& a) {
  if (a.node == kMorphTracksNode) {
    switch (a.param) {
      case int(MorphTrack::Easing): return "easing";
      case int(MorphTrack::Blend): return "blend w(u)";
      case int(MorphTrack::NoiseAmplitude): return "noise amplitude";
      default: return "morph track " + std::to_string(a.param);
    }
  }
  std::string s = std::string(slotName(MorphSlot(std::clamp(a.node, 0, 1)))) + " segment " + std::to_string(a.point);
  if (a.param >= 0 && a.param < 3) s += std::string(" ") + kSegmentChannelNames[a.param];
  return s;
}

TrackSet morphTrackSet(MorphSetup& m) {
  TrackSet set;
  set.find = [&m](const ParamAddress& a) { return findMorphTrack(m, a); };
  set.name = [](const ParamAddress& a) { return "morph " + morphTrackName(a); };
  set.clampValue = [](const ParamAddress& a, float v) {
    bool nonNegative = a.node != kMorphTracksNode ? a.param == int(SegmentChannel::RadiusScale)
                                                  : a.param == int(MorphTrack::NoiseAmplitude);
    return nonNegative ? std::max(0.0f, v) : v;
  };
  set.minTimeSec = 0.0;
  set.maxTimeSec = 1.0;
  return set;
}

std::vector<ParamAddress> morphTrackAddresses(const MorphSetup& m) {
  std::vector<ParamAddress> out = {morphTrackAddress(MorphTrack::Easing), morphTrackAddress(MorphTrack::Blend),
                                   morphTrackAddress(MorphTrack::NoiseAmplitude)};
  for (MorphSlot slot : {MorphSlot::Source, MorphSlot::Target}) {
    const ActorMorph* a = slotActor(m, slot);
    if (!a) continue;
    std::vector<int> segs;
    for (const auto& t : a->segmentTracks) segs.push_back(t.segment);
    std::sort(segs.begin(), segs.end());
    for (int s : segs)
      for (SegmentChannel c : {SegmentChannel::AOffset, SegmentChannel::BOffset, SegmentChannel::RadiusScale})
        out.push_back(segmentTrackAddress(slot, s, c));
  }
  return out;
}

double morphProgressAt(const MorphSetup& m, double frame) {
  const MorphMarkers& k = m.markers;
  if (k.c <= k.b) return frame < k.b ? 0.0 : 1.0;
  return std::clamp((frame - k.b) / double(k.c - k.b), 0.0, 1.0);
}

double transitionProgressAt(const MorphSetup& m, double frame) {
  const MorphMarkers& k = m.markers;
  auto frac = [&](int a, int b) { return b > a ? std::clamp((frame - a) / double(b - a), 0.0, 1.0) : 1.0; };
  if (frame >= k.a && frame < k.b) return frac(k.a, k.b);
  if (frame > k.c && frame <= k.d) return frac(k.c, k.d);
  return -1.0;
}

std::unique_ptr<Command> setMorphTracksCommand(const Project& p, const MorphSetup& after, std::string label,
                                               std::string mergeKey) {
  return std::make_unique<MorphTracksCommand>(p.morph, after, std::move(label), std::move(mergeKey));
}

Result<std::unique_ptr<Command>> setSegmentTrackCommand(const Project& p, MorphSlot slot, int segment,
                                                        SegmentChannel c, double u, const ParamSample& value,
                                                        bool key, std::string mergeKey) {
  const std::string where = std::string("morph ") + slotName(slot) + " segment " + std::to_string(segment);
  if (!std::isfinite(u)) return Error{where + ": progress u is not finite"};
  u = std::clamp(u, 0.0, 1.0);
  const std::string label = std::string(key ? "Key " : "Set ") + slotName(slot) + " segment " +
                            std::to_string(segment) + " " + kSegmentChannelNames[int(c)];
  return editMorphTracks(
      p, label,
      [&](MorphSetup& m) -> Status {
        ActorMorph* a = slotActor(m, slot);
        if (!a) return Error{std::string("morph: no ") + slotName(slot) + " actor"};
        if (segment < 0 || segment >= int(a->standin.segments.size()))
          return Error{where + ": the stand-in has " + std::to_string(a->standin.segments.size()) + " segments"};
        SegmentTracks* st = findSegmentTracks(*a, segment);
        if (!st) {
          SegmentTracks fresh;
          fresh.segment = segment;
          fresh.aOffset = neutralTrack(glm::vec3(0.0f));
          fresh.bOffset = neutralTrack(glm::vec3(0.0f));
          fresh.radiusScale = neutralTrack(1.0f);
          a->segmentTracks.push_back(fresh);
          st = &a->segmentTracks.back();
        }
        if (c == SegmentChannel::RadiusScale) {
          const float* v = std::get_if<float>(&value);
          if (!v || !std::isfinite(*v)) return Error{where + ": radius scale must be a finite number"};
          setTrackValue(st->radiusScale, u, std::max(0.0f, *v), key);
        } else {
          const glm::vec3* v = std::get_if<glm::vec3>(&value);
          if (!v || !std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z))
            return Error{where + ": " + kSegmentChannelNames[int(c)] + " must be a finite vector"};
          setTrackValue(c == SegmentChannel::AOffset ? st->aOffset : st->bOffset, u, *v, key);
        }
        return Status::success();
      },
      std::move(mergeKey));
}

Result<std::unique_ptr<Command>> removeSegmentTracksCommand(const Project& p, MorphSlot slot, int segment) {
  return editMorphTracks(p, std::string("Remove ") + slotName(slot) + " segment " + std::to_string(segment) + " tracks",
                         [&](MorphSetup& m) -> Status {
                           ActorMorph* a = slotActor(m, slot);
                           if (!a || !findSegmentTracks(*a, segment))
                             return Error{std::string("morph ") + slotName(slot) + " segment " +
                                          std::to_string(segment) + ": no keyed tracks"};
                           std::erase_if(a->segmentTracks, [&](const SegmentTracks& t) { return t.segment == segment; });
                           return Status::success();
                         });
}

FloatTrack easingPresetTrack(EasingPreset p) {
  switch (p) {
    case EasingPreset::Linear: return linearBlendTrack();
    case EasingPreset::Smoothstep: return smoothstepTrack();
    case EasingPreset::EaseIn: return hermiteRampTrack(0.0f, 2.0f);   // u^2
    case EasingPreset::EaseOut: return hermiteRampTrack(2.0f, 0.0f);  // 1 - (1 - u)^2
  }
  return linearBlendTrack();
}

const char* easingPresetName(EasingPreset p) {
  switch (p) {
    case EasingPreset::Linear: return "linear";
    case EasingPreset::Smoothstep: return "smoothstep";
    case EasingPreset::EaseIn: return "ease-in";
    case EasingPreset::EaseOut: return "ease-out";
  }
  return "linear";
}

}  // namespace animorph
