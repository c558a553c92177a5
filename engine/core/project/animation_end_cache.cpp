#include "core/project/animation_end_cache.h"

#include <atomic>
#include <functional>
#include <map>
#include <mutex>
#include <utility>

#include "core/blobtree/tree_edit.h"

namespace animorph {

namespace {

struct KeptEnd {
  uint64_t revision = 0;
  double endSec = 0.0;
};

// Entries are few (one per BlobTree actor of each open project); a new revision overwrites its
// tree's entry, and the map is emptied when it outgrows that (trees moved by new actors).
constexpr size_t kMaxKeptEnds = 256;

std::mutex& endsMutex() {
  static std::mutex m;
  return m;
}

std::map<std::pair<const void*, const BlobTree*>, KeptEnd>& keptEnds() {
  static std::map<std::pair<const void*, const BlobTree*>, KeptEnd> ends;
  return ends;
}

std::atomic<uint64_t> g_walks{0};

thread_local const AnimationEndScope* t_innermost = nullptr;

}  // namespace

double cachedAnimationEndSec(const BlobTree& tree, const void* owner, uint64_t revision) {
  const std::pair<const void*, const BlobTree*> key{owner, &tree};
  {
    std::lock_guard<std::mutex> lock(endsMutex());
    auto it = keptEnds().find(key);
    if (it != keptEnds().end() && it->second.revision == revision) return it->second.endSec;
  }
  // Walked outside the lock: two threads asking at once both walk and store the same value.
  const double end = animationEndSec(tree);
  g_walks.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(endsMutex());
  auto& ends = keptEnds();
  if (ends.size() >= kMaxKeptEnds && !ends.count(key)) ends.clear();
  ends[key] = KeptEnd{revision, end};
  return end;
}

uint64_t animationEndWalks() { return g_walks.load(std::memory_order_relaxed); }

AnimationEndScope::AnimationEndScope(const Project& project, const void* owner, uint64_t revision)
    : project_(project), owner_(owner), revision_(revision), outer_(t_innermost) {
  t_innermost = this;
}

AnimationEndScope::~AnimationEndScope() { t_innermost = outer_; }

double AnimationEndScope::endSec(const Actor& actor) {
  const AnimationEndScope* s = t_innermost;
  if (s) {
    const Actor* first = s->project_.actors.data();
    const Actor* last = first + s->project_.actors.size();
    std::less<const Actor*> before;
    if (!before(&actor, first) && before(&actor, last))
      return cachedAnimationEndSec(actor.blobTree, s->owner_, s->revision_);
  }
  return animationEndSec(actor.blobTree);
}

}  // namespace animorph
