#pragma once
// The tree time a BlobTree actor shows at the timeline's current frame (its offset, speed and
// loop applied): what the inspector, the gizmo, the curve editor and jobs key and evaluate at.
#include "core/doc/document.h"
#include "core/project/actor_time.h"

namespace animorph {

inline double blobTreeTimeNow(const Document& doc, const Actor& actor) {
  return blobActorTimeSec(actor, doc.project().timeline.currentTimeSec());
}

}  // namespace animorph
