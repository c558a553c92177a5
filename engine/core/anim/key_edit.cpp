#include "core/anim/key_edit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/math/euler.h"

namespace animorph {

namespace {

template <class F>
auto visitTrack(const TrackPtr& p, F&& f) {
  if (auto* t = std::get_if<FloatTrack*>(&p)) return f(**t);
  if (auto* t = std::get_if<Vec3Track*>(&p)) return f(**t);
  return f(*std::get<QuatTrack*>(p));
}

std::string nameOf(const TrackSet& set, const ParamAddress& a) {
  if (set.name) return set.name(a);
  return "track " + std::to_string(a.node) + "/" + std::to_string(a.param) + "/" + std::to_string(a.point);
}

Result<TrackPtr> trackOf(const TrackSet& set, const ParamAddress& a) {
  TrackPtr t = set.find(a);
  if (std::holds_alternative<std::monostate>(t)) return Error{nameOf(set, a) + ": no such track"};
  return t;
}

Error noKey(const TrackSet& set, const ParamAddress& a, int k) {
  return Error{nameOf(set, a) + ": no key " + std::to_string(k)};
}

}  // namespace

std::string keysLabel(const std::string& verb, size_t count) {
  return count == 1 ? verb + " key" : verb + " " + std::to_string(count) + " keys";
}

std::string interpLabel(KeyInterp interp) {
  const char* name = interp == KeyInterp::Constant ? "constant" : interp == KeyInterp::Linear ? "linear" : "Hermite";
  return std::string("Set key interpolation to ") + name;
}

ConstTrackPtr asConst(const TrackPtr& t) {
  if (auto* f = std::get_if<FloatTrack*>(&t)) return *f;
  if (auto* v = std::get_if<Vec3Track*>(&t)) return *v;
  if (auto* q = std::get_if<QuatTrack*>(&t)) return *q;
  return {};
}

float channelOf(const ParamSample& v, int channel) {
  if (auto* f = std::get_if<float>(&v)) return *f;
  if (auto* p = std::get_if<glm::vec3>(&v)) return (*p)[std::clamp(channel, 0, 2)];
  return eulerDegreesOf(std::get<glm::quat>(v))[std::clamp(channel, 0, 2)];
}

ParamSample withChannel(const ParamSample& v, int channel, float x) {
  if (std::holds_alternative<float>(v)) return x;
  int c = std::clamp(channel, 0, 2);
  if (auto* p = std::get_if<glm::vec3>(&v)) {
    glm::vec3 r = *p;
    r[c] = x;
    return r;
  }
  glm::vec3 e = eulerDegreesOf(std::get<glm::quat>(v));
  e[c] = x;
  return quatFromEulerDegrees(e);
}

int keyCount(const ConstTrackPtr& t) {
  if (auto* f = std::get_if<const FloatTrack*>(&t)) return int((*f)->keys().size());
  if (auto* v = std::get_if<const Vec3Track*>(&t)) return int((*v)->keys().size());
  if (auto* q = std::get_if<const QuatTrack*>(&t)) return int((*q)->keys().size());
  return 0;
}

bool keyAt(const ConstTrackPtr& t, int k, double& timeSec, ParamSample& value, KeyInterp* interp) {
  auto read = [&](const auto* track) {
    if (!track || k < 0 || k >= int(track->keys().size())) return false;
    const auto& key = track->keys()[size_t(k)];
    timeSec = key.timeSec;
    value = key.value;
    if (interp) *interp = key.interp;
    return true;
  };
  if (auto* f = std::get_if<const FloatTrack*>(&t)) return read(*f);
  if (auto* v = std::get_if<const Vec3Track*>(&t)) return read(*v);
  if (auto* q = std::get_if<const QuatTrack*>(&t)) return read(*q);
  return false;
}

bool sampleTrack(const ConstTrackPtr& t, double timeSec, ParamSample& value) {
  if (auto* f = std::get_if<const FloatTrack*>(&t)) value = (*f)->evaluate(timeSec);
  else if (auto* v = std::get_if<const Vec3Track*>(&t)) value = (*v)->evaluate(timeSec);
  else if (auto* q = std::get_if<const QuatTrack*>(&t)) value = (*q)->evaluate(timeSec);
  else return false;
  return true;
}

float keySlope(const ConstTrackPtr& t, int k, int channel) {
  auto slope = [&](const auto* track) -> float {
    using T = std::decay_t<decltype(track->keys()[0].value)>;
    const auto& ks = track->keys();
    if (k < 0 || k >= int(ks.size())) return 0.0f;
    T d1 = ks[size_t(k)].d1, d2{};
    if (!ks[size_t(k)].userDerivatives) catmullRomDerivatives(ks, size_t(k), d1, d2);
    if constexpr (std::is_same_v<T, float>) return d1;
    else return d1[std::clamp(channel, 0, 2)];
  };
  if (auto* f = std::get_if<const FloatTrack*>(&t)) return slope(*f);
  if (auto* v = std::get_if<const Vec3Track*>(&t)) return slope(*v);
  return 0.0f;
}

Status deleteKeys(const TrackSet& set, const std::vector<KeyRef>& keys) {
  std::map<ParamAddress, std::set<int>> byTrack;
  for (const KeyRef& k : keys) byTrack[k.param].insert(k.key);
  // Named references, not structured bindings: clang before 16 cannot capture those in a lambda.
  for (const auto& entry : byTrack) {
    const ParamAddress& addr = entry.first;
    const std::set<int>& idx = entry.second;
    auto t = trackOf(set, addr);
    if (!t) return Error{t.error()};
    Status st = visitTrack(*t, [&](auto& track) -> Status {
      auto& ks = track.keys();
      for (int i : idx)
        if (i < 0 || i >= int(ks.size())) return noKey(set, addr, i);
      auto first = ks.front();
      for (auto it = idx.rbegin(); it != idx.rend(); ++it) ks.erase(ks.begin() + *it);
      if (ks.empty()) {
        first.timeSec = std::max(0.0, set.minTimeSec);
        first.userDerivatives = false;
        ks.push_back(first);
      }
      return Status::success();
    });
    if (!st) return st;
  }
  return Status::success();
}

Result<std::vector<KeyChannelRef>> moveKeys(const TrackSet& set, const std::vector<KeyChannelRef>& channels,
                                            double dtSec, float dValue) {
  // Per track: which keys move, and which of their channels change.
  std::map<ParamAddress, std::map<int, std::set<int>>> byTrack;
  for (const auto& c : channels) byTrack[c.key.param][c.key.key].insert(c.channel);
  std::map<KeyRef, KeyRef> remap;
  for (const auto& entry : byTrack) {
    const ParamAddress& addr = entry.first;
    const std::map<int, std::set<int>>& moving = entry.second;
    auto t = trackOf(set, addr);
    if (!t) return Error{t.error()};
    Status st = visitTrack(*t, [&](auto& track) -> Status {
      using T = std::decay_t<decltype(track.keys()[0].value)>;
      auto& ks = track.keys();
      for (const auto& [i, chs] : moving)
        if (i < 0 || i >= int(ks.size())) return noKey(set, addr, i);
      struct Tagged {
        TrackKey<T> key;
        int oldIndex;
        bool moved;
      };
      std::vector<Tagged> all;
      for (size_t i = 0; i < ks.size(); ++i) {
        Tagged tg{ks[i], int(i), moving.count(int(i)) > 0};
        if (tg.moved) {
          tg.key.timeSec = std::clamp(tg.key.timeSec + dtSec, set.minTimeSec, set.maxTimeSec);
          ParamSample v = tg.key.value;
          for (int c : moving.at(int(i))) v = withChannel(v, c, channelOf(v, c) + dValue);
          T nv = std::get<T>(v);
          if constexpr (std::is_same_v<T, float>)
            if (set.clampValue) nv = set.clampValue(addr, nv);
          tg.key.value = nv;
        }
        all.push_back(tg);
      }
      // Moved keys replace unmoved ones at the same time.
      std::vector<Tagged> kept;
      for (const auto& a : all) {
        bool covered = false;
        if (!a.moved)
          for (const auto& b : all)
            if (b.moved && std::abs(b.key.timeSec - a.key.timeSec) < kSameKeyTimeSec) covered = true;
        if (!covered) kept.push_back(a);
      }
      std::stable_sort(kept.begin(), kept.end(),
                       [](const Tagged& x, const Tagged& y) { return x.key.timeSec < y.key.timeSec; });
      // Two moved keys on one time: the later in the list wins.
      std::vector<Tagged> uniq;
      for (const auto& k : kept) {
        if (!uniq.empty() && std::abs(uniq.back().key.timeSec - k.key.timeSec) < kSameKeyTimeSec) uniq.back() = k;
        else uniq.push_back(k);
      }
      ks.clear();
      for (size_t i = 0; i < uniq.size(); ++i) {
        ks.push_back(uniq[i].key);
        if (uniq[i].moved) remap[KeyRef{addr, uniq[i].oldIndex}] = KeyRef{addr, int(i)};
      }
      return Status::success();
    });
    if (!st) return Error{st.error()};
  }
  std::vector<KeyChannelRef> out;
  for (const auto& c : channels) {
    auto it = remap.find(c.key);
    if (it != remap.end()) out.push_back({it->second, c.channel});
  }
  return out;
}

Result<KeyChannelRef> setKeyTimeValue(const TrackSet& set, const KeyChannelRef& k, double timeSec, float value) {
  double t0 = 0.0;
  ParamSample v;
  if (!keyAt(asConst(set.find(k.key.param)), k.key.key, t0, v)) return noKey(set, k.key.param, k.key.key);
  if (!std::isfinite(timeSec) || !std::isfinite(value))
    return Error{nameOf(set, k.key.param) + ": key time and value must be finite"};
  auto moved = moveKeys(set, {k}, std::clamp(timeSec, set.minTimeSec, set.maxTimeSec) - t0, value - channelOf(v, k.channel));
  if (!moved) return Error{moved.error()};
  if (moved->empty()) return Error{nameOf(set, k.key.param) + ": the key vanished"};
  return moved->front();
}

Status setKeyInterp(const TrackSet& set, const std::vector<KeyRef>& keys, KeyInterp interp) {
  for (const KeyRef& k : keys) {
    auto t = trackOf(set, k.param);
    if (!t) return Error{t.error()};
    Status st = visitTrack(*t, [&](auto& track) -> Status {
      if (k.key < 0 || k.key >= int(track.keys().size())) return noKey(set, k.param, k.key);
      track.keys()[size_t(k.key)].interp = interp;
      return Status::success();
    });
    if (!st) return st;
  }
  return Status::success();
}

Status setKeyTangentMode(const TrackSet& set, const std::vector<KeyRef>& keys, bool user) {
  for (const KeyRef& k : keys) {
    auto t = trackOf(set, k.param);
    if (!t) return Error{t.error()};
    Status st = visitTrack(*t, [&](auto& track) -> Status {
      using T = std::decay_t<decltype(track.keys()[0].value)>;
      auto& ks = track.keys();
      if (k.key < 0 || k.key >= int(ks.size())) return noKey(set, k.param, k.key);
      if constexpr (!std::is_same_v<T, glm::quat>) {  // rotations slerp: no tangents
        auto& key = ks[size_t(k.key)];
        if (user && !key.userDerivatives) catmullRomDerivatives(ks, size_t(k.key), key.d1, key.d2);
        key.userDerivatives = user;
      }
      return Status::success();
    });
    if (!st) return st;
  }
  return Status::success();
}

Status setKeyTangent(const TrackSet& set, const KeyChannelRef& k, float slopePerSec) {
  auto t = trackOf(set, k.key.param);
  if (!t) return Error{t.error()};
  if (std::holds_alternative<QuatTrack*>(*t))
    return Error{nameOf(set, k.key.param) + ": rotation keys have no tangents (they slerp)"};
  if (!std::isfinite(slopePerSec)) return Error{nameOf(set, k.key.param) + ": tangent slope must be finite"};
  if (Status s = setKeyTangentMode(set, {k.key}, true); !s) return s;
  if (auto* f = std::get_if<FloatTrack*>(&*t)) (*f)->keys()[size_t(k.key.key)].d1 = slopePerSec;
  else std::get<Vec3Track*>(*t)->keys()[size_t(k.key.key)].d1[std::clamp(k.channel, 0, 2)] = slopePerSec;
  return Status::success();
}

Result<int> insertKey(const TrackSet& set, const ParamAddress& a, double timeSec) {
  auto t = trackOf(set, a);
  if (!t) return Error{t.error()};
  if (!std::isfinite(timeSec)) return Error{nameOf(set, a) + ": key time is not finite"};
  timeSec = std::clamp(timeSec, set.minTimeSec, set.maxTimeSec);
  return visitTrack(*t, [&](auto& track) -> Result<int> {
    auto value = track.evaluate(timeSec);
    bool exists = false;
    for (const auto& k : track.keys()) exists |= std::abs(k.timeSec - timeSec) < kSameKeyTimeSec;
    if (!exists) setTrackValue(track, timeSec, value, true);
    const auto& ks = track.keys();
    for (size_t i = 0; i < ks.size(); ++i)
      if (std::abs(ks[i].timeSec - timeSec) < kSameKeyTimeSec) return int(i);
    return Error{nameOf(set, a) + ": the key was not added"};
  });
}

}  // namespace animorph
