#pragma once
// The tree time a BlobTree actor shows at the timeline's current frame (its offset, speed and
// loop applied): what the inspector, the gizmo, the curve editor and jobs key and evaluate at.
#include "core/doc/document.h"
#include "core/project/actor_time.h"
#include "core/project/animation_end_cache.h"

namespace animorph {

// The tree's end is walked once per document revision (project/animation_end_cache.h).
inline double blobTreeTimeNow(const Document& doc, const Actor& actor) {
  AnimationEndScope ends(doc.project(), &doc, doc.revision());
  return blobActorTimeSec(actor, doc.project().timeline.currentTimeSec());
}

}  // namespace animorph
