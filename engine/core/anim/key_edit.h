#pragma once
// Key edits on sets of tracks (the curve editor's operations): delete / move
// keys, numeric entry, interpolation, tangents, inserting a key. The tracks
// live in some container (a BlobTree's parameters, the morph's easing, blend
// and segment tracks); a TrackSet tells the edits how to reach a track from
// its address and how to name it in errors. Every edit refuses with a
// message naming the track and the reason, and then may have left the
// container half-edited: callers edit a copy (the undoable commands do).
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "core/anim/track.h"
#include "core/util/result.h"

namespace animorph {

// One track of a container. For BlobTrees: node id, index into the node
// type's params, and for a control-point list the point index (else -1).
// Other containers give the three numbers their own meaning (doc/morph_tracks.h).
struct ParamAddress {
  int node = -1;
  int param = -1;
  int point = -1;
  bool operator==(const ParamAddress&) const = default;
  auto operator<=>(const ParamAddress&) const = default;
};

// One key of one track.
struct KeyRef {
  ParamAddress param;
  int key = -1;
  bool operator==(const KeyRef&) const = default;
  auto operator<=>(const KeyRef&) const = default;
};

// One scalar channel of one key: channel 0 for floats, 0..2 = x, y, z for
// vectors, 0..2 = Euler X, Y, Z degrees for rotations.
struct KeyChannelRef {
  KeyRef key;
  int channel = 0;
  bool operator==(const KeyChannelRef&) const = default;
  auto operator<=>(const KeyChannelRef&) const = default;
};

// A track value at one time.
using ParamSample = std::variant<float, glm::vec3, glm::quat>;

// Pointer to a track inside a container (monostate: no such track).
using TrackPtr = std::variant<std::monostate, FloatTrack*, Vec3Track*, QuatTrack*>;
using ConstTrackPtr = std::variant<std::monostate, const FloatTrack*, const Vec3Track*, const QuatTrack*>;
ConstTrackPtr asConst(const TrackPtr& t);

// How key edits reach the tracks of one container.
struct TrackSet {
  std::function<TrackPtr(const ParamAddress&)> find;
  // "node 4", "morph blend": prefixes error messages.
  std::function<std::string(const ParamAddress&)> name;
  // The value rule of a float track (radius >= 0, ...); empty: none.
  std::function<float(const ParamAddress&, float)> clampValue;
  // Key times are kept in [minTimeSec, maxTimeSec].
  double minTimeSec = 0.0;
  double maxTimeSec = std::numeric_limits<double>::infinity();
};

// Scalar channel of a value (quaternions as Euler degrees).
float channelOf(const ParamSample& v, int channel);
// v with one channel replaced (quaternions through Euler degrees).
ParamSample withChannel(const ParamSample& v, int channel, float x);

// Number of keys (0 for no track).
int keyCount(const ConstTrackPtr& t);
// Time, value and interpolation of key k; false when absent.
bool keyAt(const ConstTrackPtr& t, int k, double& timeSec, ParamSample& value, KeyInterp* interp = nullptr);
// Value at timeSec; false for no track.
bool sampleTrack(const ConstTrackPtr& t, double timeSec, ParamSample& value);
// Slope (value per time unit) of one channel at key k as the curve uses it (user or automatic); 0 for rotations.
float keySlope(const ConstTrackPtr& t, int k, int channel);

// Sets a track's value at timeSec. key = false: a track with two or more keys
// gets a key there (created, or the one there replaced, keeping its
// interpolation), a constant one just takes the value; key = true (a key
// button): a key at timeSec either way, so keying a constant at another time
// than its single key animates it.
template <class T>
void setTrackValue(Track<T>& t, double timeSec, const T& value, bool key);

// Deletes keys. A track that would lose every key keeps its first one's value as a constant.
Status deleteKeys(const TrackSet& set, const std::vector<KeyRef>& keys);
// Moves keys by dtSec in time and, per selected channel, by dValue (quaternion
// channels in degrees). A moved key landing on an unmoved key's time replaces
// it; times stop at the set's limits. Returns the channel refs of the moved
// keys after re-sorting (the selection follows its keys), in the order given.
Result<std::vector<KeyChannelRef>> moveKeys(const TrackSet& set, const std::vector<KeyChannelRef>& channels,
                                            double dtSec, float dValue);
// Sets one key channel's time and value exactly (numeric entry). Returns the key's new ref.
Result<KeyChannelRef> setKeyTimeValue(const TrackSet& set, const KeyChannelRef& k, double timeSec, float value);
// Interpolation of the segments starting at the keys.
Status setKeyInterp(const TrackSet& set, const std::vector<KeyRef>& keys, KeyInterp interp);
// Tangent mode: user (the stored d1 is used) or auto (Catmull-Rom). Switching
// to user stores the automatic slopes, so the curve does not change.
Status setKeyTangentMode(const TrackSet& set, const std::vector<KeyRef>& keys, bool user);
// Sets the slope of one channel of a key (switching it to user tangents). Not on rotations.
Status setKeyTangent(const TrackSet& set, const KeyChannelRef& k, float slopePerSec);
// Adds a key at timeSec holding the curve's value there (the curve does not
// change shape much; a key already there stays). Returns its index.
Result<int> insertKey(const TrackSet& set, const ParamAddress& a, double timeSec);

// Undo labels: "Move key" / "Move 3 keys"; "Set key interpolation to linear".
std::string keysLabel(const std::string& verb, size_t count);
std::string interpLabel(KeyInterp interp);

// ---- implementation of the templates ----
constexpr double kSameKeyTimeSec = 1e-6;  // keys closer than this are at "the same time"

template <class T>
void setTrackValue(Track<T>& t, double timeSec, const T& value, bool key) {
  auto& keys = t.keys();
  if (keys.empty()) {
    t.setKey(key ? timeSec : 0.0, value);
    return;
  }
  if (keys.size() == 1 && !key) {
    keys[0].value = value;  // no animation: the value holds at all times
    return;
  }
  for (auto& k : keys) {
    if (std::abs(k.timeSec - timeSec) < kSameKeyTimeSec) {
      k.value = value;
      return;
    }
  }
  KeyInterp interp = KeyInterp::Hermite;
  // A new key inherits the interpolation of the segment it splits.
  for (const auto& k : keys)
    if (k.timeSec < timeSec) interp = k.interp;
  t.setKey(timeSec, value, interp);
}

}  // namespace animorph
