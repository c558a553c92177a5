#include "core/doc/standin_commands.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace animorph {

namespace {

struct StandinState {
  Standin standin;
  std::vector<SegmentTracks> tracks;
};

StandinState stateOf(const ActorMorph& am) { return {am.standin, am.segmentTracks}; }

// Swaps an actor's stand-in and segment tracks between two snapshots.
class StandinStateCommand final : public Command {
 public:
  StandinStateCommand(std::string actorId, StandinState before, StandinState after, std::string label,
                      std::string mergeKey)
      : actorId_(std::move(actorId)), before_(std::move(before)), after_(std::move(after)),
        label_(std::move(label)), mergeKey_(std::move(mergeKey)) {}
  void apply(Project& p) override { put(p, after_); }
  void revert(Project& p) override { put(p, before_); }
  std::string label() const override { return label_; }
  std::string mergeKey() const override { return mergeKey_; }
  bool mergeWith(const Command& other) override {
    auto* o = dynamic_cast<const StandinStateCommand*>(&other);
    if (!o || mergeKey_.empty() || o->mergeKey_ != mergeKey_ || o->actorId_ != actorId_) return false;
    after_ = o->after_;
    return true;
  }

 private:
  void put(Project& p, const StandinState& s) const {
    if (ActorMorph* am = p.morph.findActor(actorId_)) {
      am->standin = s.standin;
      am->segmentTracks = s.tracks;
    }
  }
  std::string actorId_;
  StandinState before_, after_;
  std::string label_, mergeKey_;
};

// Runs edit on a copy of the actor's morph data; the command swapping it in.
template <class Edit>
Result<std::unique_ptr<Command>> editStandin(const Project& p, const std::string& actorId, std::string label,
                                             Edit&& edit, std::string mergeKey = {}) {
  const ActorMorph* am = p.morph.findActor(actorId);
  if (!am) return Error{"actor '" + actorId + "' has no stand-in (it is not part of the morph)"};
  ActorMorph copy = *am;
  copy.weightMap.clear();  // not part of the snapshot
  Status s = edit(copy);
  if (!s) return Error{"actor '" + actorId + "': " + s.error()};
  std::unique_ptr<Command> cmd = std::make_unique<StandinStateCommand>(actorId, stateOf(*am), stateOf(copy),
                                                                       std::move(label), std::move(mergeKey));
  return cmd;
}

Status checkIndex(const ActorMorph& am, int index) {
  if (index < 0 || index >= int(am.standin.segments.size()))
    return Error{"stand-in segment " + std::to_string(index) + " does not exist (" +
                 std::to_string(am.standin.segments.size()) + " segments)"};
  return {};
}

Status checkSegment(const StandinSegment& s) {
  if (!(s.radius > 0.0f) || !std::isfinite(s.radius)) return Error{"a segment's radius must be positive"};
  for (const glm::vec3& v : {s.a, s.b})
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      return Error{"a segment's ends must be finite"};
  return {};
}

}  // namespace

void insertStandinSegment(ActorMorph& am, int at, const StandinSegment& seg) {
  at = std::clamp(at, 0, int(am.standin.segments.size()));
  am.standin.segments.insert(am.standin.segments.begin() + at, seg);
  for (SegmentTracks& t : am.segmentTracks)
    if (t.segment >= at) ++t.segment;
}

bool eraseStandinSegment(ActorMorph& am, int index) {
  if (index < 0 || index >= int(am.standin.segments.size())) return false;
  am.standin.segments.erase(am.standin.segments.begin() + index);
  auto& tr = am.segmentTracks;
  tr.erase(std::remove_if(tr.begin(), tr.end(), [&](const SegmentTracks& t) { return t.segment == index; }), tr.end());
  for (SegmentTracks& t : tr)
    if (t.segment > index) --t.segment;
  return true;
}

size_t replaceStandin(ActorMorph& am, Standin after) {
  // The k-th segment on a node, before and after.
  auto rank = [](const Standin& s) {
    std::vector<std::pair<int, int>> r(s.segments.size());
    std::map<int, int> seen;
    for (size_t i = 0; i < s.segments.size(); ++i) r[i] = {s.segments[i].node, seen[s.segments[i].node]++};
    return r;
  };
  const auto oldRank = rank(am.standin), newRank = rank(after);
  size_t dropped = 0;
  std::vector<SegmentTracks> kept;
  for (SegmentTracks t : am.segmentTracks) {
    int to = -1;
    if (t.segment >= 0 && t.segment < int(oldRank.size())) {
      auto it = std::find(newRank.begin(), newRank.end(), oldRank[size_t(t.segment)]);
      if (it != newRank.end()) to = int(it - newRank.begin());
    }
    if (to < 0) {
      ++dropped;
      continue;
    }
    t.segment = to;
    kept.push_back(std::move(t));
  }
  am.segmentTracks = std::move(kept);
  am.standin = std::move(after);
  return dropped;
}

Result<std::unique_ptr<Command>> setStandinSegmentCommand(const Project& p, const std::string& actorId, int index,
                                                          const StandinSegment& after, std::string label,
                                                          std::string mergeKey) {
  return editStandin(
      p, actorId, std::move(label),
      [&](ActorMorph& am) -> Status {
        if (Status s = checkIndex(am, index); !s) return s;
        if (Status s = checkSegment(after); !s) return s;
        am.standin.segments[size_t(index)] = after;
        return {};
      },
      std::move(mergeKey));
}

Result<std::unique_ptr<Command>> insertStandinSegmentCommand(const Project& p, const std::string& actorId, int at,
                                                             const StandinSegment& seg, std::string label) {
  return editStandin(p, actorId, std::move(label), [&](ActorMorph& am) -> Status {
    if (Status s = checkSegment(seg); !s) return s;
    insertStandinSegment(am, at, seg);
    return {};
  });
}

Result<std::unique_ptr<Command>> deleteStandinSegmentCommand(const Project& p, const std::string& actorId, int index) {
  return editStandin(p, actorId, "Delete stand-in segment " + std::to_string(index), [&](ActorMorph& am) -> Status {
    if (Status s = checkIndex(am, index); !s) return s;
    eraseStandinSegment(am, index);
    return {};
  });
}

Result<std::unique_ptr<Command>> replaceStandinCommand(const Project& p, const std::string& actorId, Standin after,
                                                       std::string label) {
  return editStandin(p, actorId, std::move(label), [&](ActorMorph& am) -> Status {
    for (const StandinSegment& s : after.segments)
      if (Status st = checkSegment(s); !st) return st;
    replaceStandin(am, std::move(after));
    return {};
  });
}

}  // namespace animorph
