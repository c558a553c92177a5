#include "core/project/morph_setup.h"

#include "core/anim/track_json.h"
#include "core/standin_morph/transition.h"

namespace animorph {

FloatTrack linearBlendTrack() {
  FloatTrack t;
  t.clearKeys();
  t.setKey(0.0, 0.0f, KeyInterp::Linear);
  t.setKey(1.0, 1.0f, KeyInterp::Linear);
  return t;
}

MorphSetup::MorphSetup() : easing(smoothstepTrack()), blend(linearBlendTrack()) {}

ActorMorph* MorphSetup::findActor(const std::string& id) {
  for (auto& a : actors)
    if (a.actorId == id) return &a;
  return nullptr;
}

const ActorMorph* MorphSetup::findActor(const std::string& id) const {
  for (const auto& a : actors)
    if (a.actorId == id) return &a;
  return nullptr;
}

namespace {

// Tracks compare by what is saved (a driver is not part of the document).
template <class T>
bool sameTrack(const Track<T>& a, const Track<T>& b) {
  return trackToJson(a) == trackToJson(b);
}

}  // namespace

bool MorphSetup::operator==(const MorphSetup& o) const {
  if (sourceActorId != o.sourceActorId || targetActorId != o.targetActorId || !(markers == o.markers) ||
      method != o.method || correspondenceBlend != o.correspondenceBlend || chainPairs != o.chainPairs || interpolationBound != o.interpolationBound || !(spaceTime == o.spaceTime) || !sameTrack(easing, o.easing) || !sameTrack(blend, o.blend) ||
      weightMapShift != o.weightMapShift || !sameTrack(noiseAmplitude, o.noiseAmplitude) ||
      noiseFrequency != o.noiseFrequency || !(projection == o.projection) || !(crossFade == o.crossFade) ||
      actors.size() != o.actors.size())
    return false;
  for (size_t i = 0; i < actors.size(); ++i) {
    const ActorMorph &x = actors[i], &y = o.actors[i];
    if (x.actorId != y.actorId || !(x.standin == y.standin) || x.weightMap != y.weightMap ||
        x.segmentTracks.size() != y.segmentTracks.size())
      return false;
    for (size_t k = 0; k < x.segmentTracks.size(); ++k) {
      const SegmentTracks &p = x.segmentTracks[k], &q = y.segmentTracks[k];
      if (p.segment != q.segment || !sameTrack(p.aOffset, q.aOffset) || !sameTrack(p.bOffset, q.bOffset) ||
          !sameTrack(p.radiusScale, q.radiusScale))
        return false;
    }
  }
  return true;
}

}  // namespace animorph
