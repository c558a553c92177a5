#pragma once
// The last key time of a BlobTree actor's tree (blobtree/tree_edit.h animationEndSec), kept
// per revision of the project that holds it. The editor asks for it several times a frame (the
// scene evaluation's looped tree time, the inspector, the selection's bounds), and a walk over
// every key of an animorphosis demo creature costs about a millisecond. Keys change only by an
// edit, an undo, a redo or a load, and each of those gives the Document a new revision(), so a
// tree is walked once per revision.
#include <cstdint>

#include "core/project/project.h"

namespace animorph {

// animationEndSec(tree) for a tree inside the project data that owner (the Document) holds at
// revision (its revision()). Walks the tree only the first time the pair (owner, tree) asks at
// that revision; another revision walks it again. The caller promises that owner's project does
// not change without a new revision. Thread-safe.
double cachedAnimationEndSec(const BlobTree& tree, const void* owner, uint64_t revision);

// How many trees cachedAnimationEndSec has walked since the process started (tests count it).
uint64_t animationEndWalks();

// While one is alive on this thread, blobActorTimeSec (project/actor_time.h) of an actor of
// project (an element of project.actors) takes the tree's end from cachedAnimationEndSec(owner,
// revision) instead of walking the tree: the editor opens one around its scene evaluation.
// project must not change while the scope lives. Scopes nest; the innermost one is asked.
class AnimationEndScope {
 public:
  AnimationEndScope(const Project& project, const void* owner, uint64_t revision);
  ~AnimationEndScope();
  AnimationEndScope(const AnimationEndScope&) = delete;
  AnimationEndScope& operator=(const AnimationEndScope&) = delete;

  // The end of actor's tree: cached when actor belongs to the innermost scope's project on this
  // thread, walked (animationEndSec) otherwise.
  static double endSec(const Actor& actor);

 private:
  const Project& project_;
  const void* owner_;
  uint64_t revision_;
  const AnimationEndScope* outer_;
};

}  // namespace animorph
