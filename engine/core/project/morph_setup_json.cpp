#include "core/project/morph_setup_json.h"

#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>

#include "core/anim/track_json.h"
#include "core/util/json_fields.h"
#include "core/util/base64.h"
#include "core/project/project_io.h"
#include "core/standin/standin_json.h"
#include "core/util/json_text.h"

namespace animorph {

using json = nlohmann::json;

json morphSetupToJson(const MorphSetup& m) {
  json j;
  j["source"] = m.sourceActorId;
  j["target"] = m.targetActorId;
  j["markers"] = {{"A", m.markers.a}, {"B", m.markers.b}, {"C", m.markers.c}, {"D", m.markers.d}};
  j["method"] = morphMethodName(m.method);
  if (m.correspondenceBlend != MorphMethod::Interpolation)  // written when set: older projects stay byte-identical
    j["correspondence_blend"] = morphMethodName(m.correspondenceBlend);
  if (!m.chainPairs.empty()) {  // written when set: older projects stay byte-identical
    json pairs = json::array();
    for (const ChainPair& p : m.chainPairs)
      pairs.push_back({{"source", p.source}, {"target", p.target ? json(*p.target) : json(nullptr)}});
    j["chain_pairs"] = pairs;
  }
  if (m.interpolationBound != kDefaultInterpolationBound) j["interpolation_bound"] = m.interpolationBound;
  const SpaceTimeParams& st = m.spaceTime;
  j["space_time"] = {{"time_scale", st.timeScale}, {"a0", st.a0}, {"a1", st.a1}, {"a2", st.a2}, {"a3", st.a3}};
  j["easing"] = trackToJson(m.easing);
  j["blend"] = trackToJson(m.blend);
  j["weight_map_shift"] = m.weightMapShift;
  j["noise"] = {{"amplitude", trackToJson(m.noiseAmplitude)}, {"frequency", m.noiseFrequency}};
  const MorphProjection& p = m.projection;
  j["projection"] = {{"pose", p.atClipTime ? "clip" : "rest"}, {"clip_time", p.clipTimeSec},
                     {"max_iterations", p.maxIterations}, {"tolerance", p.tolerance},
                     {"max_step_radii", p.maxStepRadii}, {"reproject_from", p.reprojectFrom}};
  if (!(m.crossFade == MorphCrossFade{}))  // written when set, so projects without it stay byte-identical
    j["cross_fade"] = {{"enabled", m.crossFade.enabled}, {"width_frames", m.crossFade.widthFrames}};
  json actors = json::array();
  for (const ActorMorph& a : m.actors) {
    json ja = {{"id", a.actorId}, {"standin", standinToJson(a.standin)}};
    if (!a.weightMap.empty()) ja["weight_map"] = floatsToBase64(a.weightMap);
    if (!a.segmentTracks.empty()) {
      json tracks = json::array();
      for (const SegmentTracks& t : a.segmentTracks)
        tracks.push_back({{"segment", t.segment},
                          {"a_offset", trackToJson(t.aOffset)},
                          {"b_offset", trackToJson(t.bOffset)},
                          {"radius_scale", trackToJson(t.radiusScale)}});
      ja["segment_tracks"] = tracks;
    }
    actors.push_back(ja);
  }
  j["actors"] = actors;
  return j;
}

namespace {

// Fields whose own range check follows are read as any int (never wrapped).
constexpr int kIntMin = std::numeric_limits<int>::min();
constexpr int kIntMax = std::numeric_limits<int>::max();

using Parser = JsonFieldReader;

// The artist's chain pairs: [{"source": JOINT, "target": JOINT or null}], one per
// source chain. Names are checked against the rigs when the morph is prepared.
std::vector<ChainPair> chainPairsFromJson(Parser& r, const json& j, const std::string& where) {
  std::vector<ChainPair> out;
  if (!j.is_array()) {
    r.fail(where, "expected an array of {\"source\": JOINT, \"target\": JOINT or null}");
    return out;
  }
  for (size_t i = 0; r.ok() && i < j.size(); ++i) {
    const std::string wi = where + "[" + std::to_string(i) + "]";
    if (!j[i].is_object()) { r.fail(wi, "expected an object {\"source\": JOINT, \"target\": JOINT or null}"); break; }
    ChainPair p;
    p.source = r.requiredString(j[i], "source", wi);
    if (r.ok() && p.source.empty()) r.fail(wi + ".source", "expected a joint name");
    if (r.ok() && !j[i].contains("target")) r.fail(wi + ".target", "missing (a joint name, or null: left unmatched)");
    if (!r.ok()) break;
    const json& t = j[i]["target"];
    if (t.is_string() && !t.get<std::string>().empty()) p.target = t.get<std::string>();
    else if (!t.is_null()) { r.fail(wi + ".target", "expected a joint name, or null: left unmatched"); break; }
    for (const ChainPair& q : out)
      if (q.source == p.source) r.fail(wi + ".source", "chain '" + p.source + "' is already paired by an earlier entry");
    out.push_back(std::move(p));
  }
  return out;
}

// "markers": {A, B, C, D} in frames, in order.
void markersFromJson(Parser& r, const json& mk, const std::string& w, MorphMarkers& markers) {
  if (!mk.is_object()) {
    r.fail(w + ".markers", "expected an object {A, B, C, D}");
    return;
  }
  markers.a = r.integer(mk, "A", w + ".markers", markers.a, -kMaxFrame, kMaxFrame);
  markers.b = r.integer(mk, "B", w + ".markers", markers.b, -kMaxFrame, kMaxFrame);
  markers.c = r.integer(mk, "C", w + ".markers", markers.c, -kMaxFrame, kMaxFrame);
  markers.d = r.integer(mk, "D", w + ".markers", markers.d, -kMaxFrame, kMaxFrame);
  if (r.ok() && markers.b < markers.a) r.fail(w + ".markers.B", "is before A");
  if (r.ok() && markers.c < markers.b) r.fail(w + ".markers.C", "is before B");
  if (r.ok() && markers.d < markers.c) r.fail(w + ".markers.D", "is before C");
}

// "method" and "correspondence_blend" (absent: interpolation).
void methodsFromJson(Parser& r, const json& j, const std::string& w, MorphSetup& m) {
  if (r.ok() && j.contains("method")) {
    const json& me = j["method"];
    if (!me.is_string() || !morphMethodFromName(me.get<std::string>(), m.method))
      r.fail(w + ".method", "expected \"interpolation\", \"space_time\" or \"skeleton_correspondence\"");
  }
  if (r.ok() && j.contains("correspondence_blend")) {  // absent: interpolation
    const json& cb = j["correspondence_blend"];
    if (!cb.is_string() || !morphMethodFromName(cb.get<std::string>(), m.correspondenceBlend) ||
        m.correspondenceBlend == MorphMethod::SkeletonCorrespondence)
      r.fail(w + ".correspondence_blend", "expected \"interpolation\" or \"space_time\"");
  }
}

// "space_time": {time_scale, a0..a3}.
void spaceTimeFromJson(Parser& r, const json& s, const std::string& w, SpaceTimeParams& p) {
  const std::string ws = w + ".space_time";
  if (!s.is_object()) {
    r.fail(ws, "expected an object");
    return;
  }
  p.timeScale = float(r.number(s, "time_scale", ws, p.timeScale));
  p.a0 = float(r.number(s, "a0", ws, p.a0));
  p.a1 = float(r.number(s, "a1", ws, p.a1));
  p.a2 = float(r.number(s, "a2", ws, p.a2));
  p.a3 = float(r.number(s, "a3", ws, p.a3));
  if (r.ok() && !(p.timeScale > 0.0f)) r.fail(ws + ".time_scale", "must be positive");
  if (r.ok() && p.a0 < 0.0f) r.fail(ws + ".a0", "must not be negative");
  if (r.ok() && !(p.a1 > 0.0f && p.a2 > 0.0f && p.a3 > 0.0f)) r.fail(ws, "a1, a2 and a3 must be positive");
}

// "noise": {amplitude (a track), frequency}.
void noiseFromJson(Parser& r, const json& n, const std::string& w, MorphSetup& m) {
  if (!n.is_object()) {
    r.fail(w + ".noise", "expected an object");
    return;
  }
  m.noiseAmplitude = r.nested(n, "amplitude", w + ".noise", &floatTrackFromJson, m.noiseAmplitude);
  m.noiseFrequency = float(r.number(n, "frequency", w + ".noise", m.noiseFrequency));
  if (r.ok() && !(m.noiseFrequency > 0.0f)) r.fail(w + ".noise.frequency", "must be positive");
}

// "projection": the pose projected onto and the projection's iteration settings.
void projectionFromJson(Parser& r, const json& p, const std::string& w, MorphProjection& mp) {
  const std::string wp = w + ".projection";
  if (!p.is_object()) {
    r.fail(wp, "expected an object");
    return;
  }
  if (p.contains("pose")) {
    if (p["pose"] == "rest") mp.atClipTime = false;
    else if (p["pose"] == "clip") mp.atClipTime = true;
    else r.fail(wp + ".pose", "expected \"rest\" or \"clip\"");
  }
  mp.clipTimeSec = r.number(p, "clip_time", wp, mp.clipTimeSec);
  mp.maxIterations = r.integer(p, "max_iterations", wp, mp.maxIterations, kIntMin, kIntMax);
  mp.tolerance = float(r.number(p, "tolerance", wp, mp.tolerance));
  mp.maxStepRadii = float(r.number(p, "max_step_radii", wp, mp.maxStepRadii));
  mp.reprojectFrom = float(r.number(p, "reproject_from", wp, mp.reprojectFrom));
  if (r.ok() && !(mp.maxIterations >= 1 && mp.maxIterations <= 1000)) r.fail(wp + ".max_iterations", "must be in 1..1000");
  if (r.ok() && !(mp.tolerance > 0.0f)) r.fail(wp + ".tolerance", "must be positive");
  if (r.ok() && !(mp.maxStepRadii > 0.0f)) r.fail(wp + ".max_step_radii", "must be positive");
  if (r.ok() && !(mp.reprojectFrom >= 0.0f && mp.reprojectFrom <= 1.0f)) r.fail(wp + ".reproject_from", "must be in [0, 1]");
}

// "cross_fade": {enabled, width_frames} (absent in older projects: off).
void crossFadeFromJson(Parser& r, const json& c, const std::string& w, MorphSetup& m) {
  const std::string wc = w + ".cross_fade";
  if (!c.is_object()) {
    r.fail(wc, "expected an object {enabled, width_frames}");
    return;
  }
  if (c.contains("enabled")) {
    if (c["enabled"].is_boolean()) m.crossFade.enabled = c["enabled"].get<bool>();
    else r.fail(wc + ".enabled", "expected true or false");
  }
  m.crossFade.widthFrames = r.integer(c, "width_frames", wc, m.crossFade.widthFrames, kIntMin, kIntMax);
  if (r.ok() && !(m.crossFade.widthFrames >= 1 && m.crossFade.widthFrames <= 1000))
    r.fail(wc + ".width_frames", "must be in 1..1000");
}

// An actor's "segment_tracks": per stand-in segment, its end offsets' and radius scale's tracks.
void segmentTracksFromJson(Parser& r, const json& ts, const std::string& wa, ActorMorph& am) {
  if (!ts.is_array()) r.fail(wa + ".segment_tracks", "expected an array");
  for (size_t k = 0; r.ok() && k < ts.size(); ++k) {
    const std::string wt = wa + ".segment_tracks[" + std::to_string(k) + "]";
    if (!ts[k].is_object()) { r.fail(wt, "expected an object"); break; }
    SegmentTracks st;
    st.segment = r.integer(ts[k], "segment", wt, -1, kIntMin, kIntMax);
    if (r.ok() && !(st.segment >= 0 && st.segment < static_cast<int>(am.standin.segments.size())))
      r.fail(wt + ".segment", "no segment " + std::to_string(st.segment) + " in the stand-in (" +
                                  std::to_string(am.standin.segments.size()) + " segments)");
    if (r.ok()) st.aOffset = r.nested(ts[k], "a_offset", wt, &vec3TrackFromJson, st.aOffset);
    if (r.ok()) st.bOffset = r.nested(ts[k], "b_offset", wt, &vec3TrackFromJson, st.bOffset);
    if (r.ok()) st.radiusScale = r.nested(ts[k], "radius_scale", wt, &floatTrackFromJson, st.radiusScale);
    am.segmentTracks.push_back(std::move(st));
  }
}

// One entry of "actors": an actor's stand-in, weight map and segment tracks. Returns false (the
// reader failed) when the entry is not to be kept.
bool actorMorphFromJson(Parser& r, const json& a, const std::string& wa, const MorphSetup& m,
                        const std::function<bool(const std::string&)>& known, ActorMorph& am) {
  if (!a.is_object()) { r.fail(wa, "expected an object"); return false; }
  am.actorId = r.requiredString(a, "id", wa);
  if (r.ok() && !known(am.actorId)) r.fail(wa + ".id", "no actor with id '" + am.actorId + "'");
  if (r.ok() && m.findActor(am.actorId)) r.fail(wa + ".id", "duplicate entry for '" + am.actorId + "'");
  if (!r.ok()) return false;
  if (!a.contains("standin")) { r.fail(wa + ".standin", "missing"); return false; }
  auto s = standinFromJson(a["standin"], wa + ".standin");
  if (!s) { r.failWith(s.error()); return false; }
  am.standin = std::move(*s);
  if (a.contains("weight_map")) {
    if (!a["weight_map"].is_string()) { r.fail(wa + ".weight_map", "expected a base64 string"); return false; }
    auto wm = floatsFromBase64(a["weight_map"].get<std::string>(), wa + ".weight_map");
    if (!wm) { r.failWith(wm.error()); return false; }
    for (size_t k = 0; k < wm->size(); ++k)
      if ((*wm)[k] < 0.0f || (*wm)[k] > 1.0f) {
        r.fail(wa + ".weight_map[" + std::to_string(k) + "]", "must be in [0, 1]");
        break;
      }
    am.weightMap = std::move(*wm);
  }
  if (r.ok() && a.contains("segment_tracks")) segmentTracksFromJson(r, a["segment_tracks"], wa, am);
  return true;
}

}  // namespace

Result<MorphSetup> morphSetupFromJson(const json& j, const std::string& sourceName,
                                      const std::vector<std::string>& actorIds) {
  Parser r(sourceName);
  const std::string w = "morph";
  if (!j.is_object()) return Error{sourceName + ": morph: expected an object"};
  MorphSetup m;
  const std::function<bool(const std::string&)> known = [&](const std::string& id) {
    return std::find(actorIds.begin(), actorIds.end(), id) != actorIds.end();
  };
  m.sourceActorId = r.requiredString(j, "source", w);
  m.targetActorId = r.requiredString(j, "target", w);
  if (r.ok() && !known(m.sourceActorId)) r.fail(w + ".source", "no actor with id '" + m.sourceActorId + "'");
  if (r.ok() && !known(m.targetActorId)) r.fail(w + ".target", "no actor with id '" + m.targetActorId + "'");
  if (r.ok() && m.sourceActorId == m.targetActorId) r.fail(w + ".target", "is the same actor as the source");
  if (r.ok() && j.contains("markers")) markersFromJson(r, j["markers"], w, m.markers);
  methodsFromJson(r, j, w, m);
  if (r.ok() && j.contains("chain_pairs")) m.chainPairs = chainPairsFromJson(r, j["chain_pairs"], w + ".chain_pairs");
  if (r.ok() && j.contains("interpolation_bound")) {  // absent: the default bound
    m.interpolationBound = float(r.number(j, "interpolation_bound", w, m.interpolationBound));
    if (r.ok() && !(m.interpolationBound >= 0.0f && m.interpolationBound <= 1e6f))
      r.fail(w + ".interpolation_bound", "expected 0 (unbounded) or a bound above 1, in units of T");
  }
  if (r.ok() && j.contains("space_time")) spaceTimeFromJson(r, j["space_time"], w, m.spaceTime);
  if (r.ok()) m.easing = r.nested(j, "easing", w, &floatTrackFromJson, m.easing);
  if (r.ok()) m.blend = r.nested(j, "blend", w, &floatTrackFromJson, m.blend);
  if (r.ok()) {
    m.weightMapShift = float(r.number(j, "weight_map_shift", w, m.weightMapShift));
    if (r.ok() && !(m.weightMapShift >= 0.0f && m.weightMapShift < 1.0f))
      r.fail(w + ".weight_map_shift", "must be in [0, 1)");
  }
  if (r.ok() && j.contains("noise")) noiseFromJson(r, j["noise"], w, m);
  if (r.ok() && j.contains("projection")) projectionFromJson(r, j["projection"], w, m.projection);
  if (r.ok() && j.contains("cross_fade")) crossFadeFromJson(r, j["cross_fade"], w, m);
  if (r.ok() && j.contains("actors")) {
    const json& actors = j["actors"];
    if (!actors.is_array()) r.fail(w + ".actors", "expected an array");
    for (size_t i = 0; r.ok() && i < actors.size(); ++i) {
      ActorMorph am;
      if (!actorMorphFromJson(r, actors[i], w + ".actors[" + std::to_string(i) + "]", m, known, am)) break;
      m.actors.push_back(std::move(am));
    }
  }
  if (!r.ok()) return Error{r.error()};
  return m;
}

}  // namespace animorph
