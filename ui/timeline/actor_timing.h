#pragma once
// An actor's clip timing fields (time offset, speed, loop), shared by the
// actor inspector and the morph panel (source and target clips). Each edit is
// a command; a drag is one undo step. The last widget drawn is the Loop box.
#include <string>

#include "core/doc/document.h"
#include "ui/widgets/drag_merge.h"

namespace animorph {

// widgetPrefix names the fields for automation: PREFIX/offset, PREFIX/speed, PREFIX/loop.
void drawActorTiming(Document& doc, const Actor& actor, DragMerge& drag, const std::string& widgetPrefix);

}  // namespace animorph
