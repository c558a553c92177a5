#include <catch2/catch.hpp>

#include "core/blobtree/tree_edit.h"
#include "core/doc/morph_tracks.h"

using namespace animorph;

namespace {

// A project with a morph between two actors whose stand-ins have 3 and 2 segments.
Project morphProject() {
  Project p;
  for (const char* id : {"src", "dst"}) {
    Actor a;
    a.id = id;
    a.name = id;
    p.actors.push_back(a);
  }
  p.morph.sourceActorId = "src";
  p.morph.targetActorId = "dst";
  for (auto [id, n] : {std::pair{"src", 3}, std::pair{"dst", 2}}) {
    ActorMorph am;
    am.actorId = id;
    for (int i = 0; i < n; ++i) am.standin.segments.push_back({i, glm::vec3(0.0f), glm::vec3(0.0f, 0.2f, 0.0f), 0.05f});
    p.morph.actors.push_back(am);
  }
  return p;
}

}  // namespace

TEST_CASE("easing presets run from 0 to 1 with their shapes", "[morph][tracks]") {
  for (EasingPreset e : {EasingPreset::Linear, EasingPreset::Smoothstep, EasingPreset::EaseIn, EasingPreset::EaseOut}) {
    FloatTrack t = easingPresetTrack(e);
    CHECK(t.evaluate(0.0) == Approx(0.0).margin(1e-6));
    CHECK(t.evaluate(1.0) == Approx(1.0));
    float prev = -1.0f;
    for (int i = 0; i <= 20; ++i) {  // monotone
      float v = t.evaluate(i / 20.0);
      CHECK(v >= prev - 1e-6f);
      prev = v;
    }
  }
  CHECK(easingPresetTrack(EasingPreset::Linear).evaluate(0.3) == Approx(0.3));
  CHECK(easingPresetTrack(EasingPreset::Smoothstep).evaluate(0.25) == Approx(0.15625));  // 3u^2 - 2u^3
  CHECK(easingPresetTrack(EasingPreset::EaseIn).evaluate(0.5) == Approx(0.25));        // u^2
  CHECK(easingPresetTrack(EasingPreset::EaseOut).evaluate(0.5) == Approx(0.75));       // 1 - (1 - u)^2
}

TEST_CASE("morph tracks are addressed, named and kept in [0, 1] by key edits", "[morph][tracks]") {
  Project p = morphProject();
  MorphSetup& m = p.morph;
  TrackSet set = morphTrackSet(m);
  const ParamAddress blend = morphTrackAddress(MorphTrack::Blend);
  REQUIRE(std::get<FloatTrack*>(findMorphTrack(m, blend)) == &m.blend);
  CHECK(morphTrackName(blend) == "blend w(u)");
  CHECK(overTransition(morphTrackAddress(MorphTrack::Easing)));
  CHECK_FALSE(overTransition(blend));
  // The last blend key cannot leave u = 1, the first cannot go below 0.
  auto moved = moveKeys(set, {{{blend, 1}, 0}}, 0.5, -0.2f);
  REQUIRE(moved);
  CHECK(m.blend.keys()[1].timeSec == Approx(1.0));
  CHECK(m.blend.keys()[1].value == Approx(0.8f));
  REQUIRE(moveKeys(set, {{{blend, 0}, 0}}, -0.3, 0.0f));
  CHECK(m.blend.keys()[0].timeSec == Approx(0.0));
  // A key in the middle on the curve, then numeric entry clamps the time.
  auto k = insertKey(set, blend, 0.5);
  REQUIRE(k);
  CHECK(*k == 1);
  CHECK(m.blend.keys().size() == 3);
  auto r = setKeyTimeValue(set, {{blend, 1}, 0}, 3.0, 0.1f);
  REQUIRE(r);
  CHECK(m.blend.keys().back().timeSec == Approx(1.0));  // replaced the key at 1
  // Noise amplitude stays non-negative; unknown tracks and keys are named in errors.
  const ParamAddress noise = morphTrackAddress(MorphTrack::NoiseAmplitude);
  REQUIRE(moveKeys(set, {{{noise, 0}, 0}}, 0.0, -1.0f));
  CHECK(m.noiseAmplitude.keys()[0].value == 0.0f);
  Status bad = deleteKeys(set, {{blend, 7}});
  REQUIRE_FALSE(bad);
  CHECK(bad.error() == "morph blend w(u): no key 7");
  Status none = setKeyInterp(set, {{segmentTrackAddress(MorphSlot::Source, 0, SegmentChannel::RadiusScale), 0}},
                             KeyInterp::Linear);
  REQUIRE_FALSE(none);
  CHECK(none.error() == "morph source segment 0 radius scale: no such track");
}

TEST_CASE("keying a segment track creates neutral tracks, and undo removes them", "[morph][tracks]") {
  Project p = morphProject();
  auto cmd = setSegmentTrackCommand(p, MorphSlot::Target, 1, SegmentChannel::RadiusScale, 0.5, 2.0f, true);
  REQUIRE(cmd);
  (*cmd)->apply(p);
  const ActorMorph* dst = slotActor(p.morph, MorphSlot::Target);
  REQUIRE(dst->segmentTracks.size() == 1);
  const SegmentTracks& t = dst->segmentTracks[0];
  CHECK(t.segment == 1);
  CHECK(t.radiusScale.evaluate(0.5) == Approx(2.0f));
  CHECK(t.radiusScale.evaluate(0.0) == Approx(1.0f));  // neutral at both ends
  CHECK(t.radiusScale.evaluate(1.0) == Approx(1.0f));
  CHECK(t.aOffset.evaluate(0.5) == glm::vec3(0.0f));
  CHECK(morphTrackAddresses(p.morph).size() == 3 + 3);
  // Typing into an animated track keys it at u as well.
  auto a = setSegmentTrackCommand(p, MorphSlot::Target, 1, SegmentChannel::AOffset, 0.25, glm::vec3(0.1f, 0, 0), false);
  REQUIRE(a);
  (*a)->apply(p);
  CHECK(slotActor(p.morph, MorphSlot::Target)->segmentTracks[0].aOffset.evaluate(0.25).x == Approx(0.1f));
  (*a)->revert(p);
  (*cmd)->revert(p);
  CHECK(slotActor(p.morph, MorphSlot::Target)->segmentTracks.empty());
  // Refusals name the segment and the reason.
  auto bad = setSegmentTrackCommand(p, MorphSlot::Target, 5, SegmentChannel::RadiusScale, 0.5, 1.0f, true);
  REQUIRE_FALSE(bad);
  CHECK(bad.error() == "morph target segment 5: the stand-in has 2 segments");
  auto nan = setSegmentTrackCommand(p, MorphSlot::Source, 0, SegmentChannel::BOffset, 0.5, glm::vec3(NAN), true);
  REQUIRE_FALSE(nan);
  CHECK_FALSE(removeSegmentTracksCommand(p, MorphSlot::Source, 0));  // nothing keyed there
}

TEST_CASE("a morph track command leaves the rest of the morph alone", "[morph][tracks]") {
  Project p = morphProject();
  auto cmd = editMorphTracks(p, "Set blend", [](MorphSetup& m) -> Status {
    m.blend = easingPresetTrack(EasingPreset::EaseIn);
    m.weightMapShift = 0.9f;  // not a track: the command does not carry it
    return Status::success();
  });
  REQUIRE(cmd);
  // Meanwhile another edit paints a weight map.
  p.morph.actors[0].weightMap = {0.5f, 0.25f};
  (*cmd)->apply(p);
  CHECK(p.morph.blend.evaluate(0.5) == Approx(0.25f));
  CHECK(p.morph.weightMapShift == 0.5f);
  CHECK(p.morph.actors[0].weightMap.size() == 2);
  (*cmd)->revert(p);
  CHECK(p.morph.blend.evaluate(0.5) == Approx(0.5f));
  CHECK(p.morph.actors[0].weightMap.size() == 2);
}

TEST_CASE("morph and transition progress at a frame", "[morph][tracks]") {
  MorphSetup m;
  m.markers = {10, 20, 40, 50};
  CHECK(morphProgressAt(m, 5) == 0.0);
  CHECK(morphProgressAt(m, 30) == Approx(0.5));
  CHECK(morphProgressAt(m, 45) == 1.0);
  CHECK(transitionProgressAt(m, 15) == Approx(0.5));
  CHECK(transitionProgressAt(m, 30) < 0.0);
  CHECK(transitionProgressAt(m, 45) == Approx(0.5));
}

TEST_CASE("BlobTree key edits go through the same TrackSet and still name the node", "[blobtree][tracks]") {
  BlobTree t = makeStarterTree();
  const BlobNode& sphere = t.root.children.at(0);
  ParamAddress radius{sphere.id, paramIndex(sphere.type, "radius"), -1};
  REQUIRE(setParamValue(t, radius, 1.0, 0.8f, true));
  REQUIRE(keyCount(t, radius) == 2);
  Status bad = deleteKeys(t, {{radius, 4}});
  REQUIRE_FALSE(bad);
  CHECK(bad.error() == "node " + std::to_string(sphere.id) + ": no key 4");
  // Radii stay non-negative when dragged down.
  REQUIRE(moveKeys(t, {{{radius, 1}, 0}}, 0.0, -5.0f));
  ParamSample v;
  double time = 0.0;
  REQUIRE(keyAt(t, {radius, 1}, time, v));
  CHECK(std::get<float>(v) >= 0.0f);
}
