#pragma once
// Create > Morph...: the modal that sets up the project's morph between any two
// of its actors (glTF characters or BlobTree actors), the method and the
// markers, as one undoable step (doc/morph_create.h); and the inspector's
// source / target pickers and swap.
#include <optional>
#include <string>

#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "core/doc/morph_create.h"
#include "ui/common/status_bar.h"

namespace animorph {

struct CreateMorphState {
  bool openNext = false;  // open the modal on the next draw
  bool isOpen = false;
  std::string sourceActorId, targetActorId;
  int method = 0;  // MorphMethod
  int markers[4] = {24, 48, 84, 108};
  std::string error;  // the last refusal, shown in the modal
  // Aligning the target to the source (doc/morph_create.h proposeTargetAlignment): by the two
  // characters' units first, then onto the source's size and place.
  bool align = true;          // apply it (one undo step with the morph)
  bool allowResize = false;   // consent to a resize beyond 10x that no unit explains
  std::string alignedFor;     // "SOURCE\nTARGET" the cached proposal is for
  std::optional<ActorAlignment> alignment;
};

// Fills the modal's fields from the project (its current morph, or the first
// two actors and markers spread over the range) and opens it next draw.
void openCreateMorph(const Document& doc, CreateMorphState& st);

// The modal; call every frame.
void drawCreateMorphPopup(Document& doc, AssetCache& assets, CreateMorphState& st, StatusMessage& status);

// The inspector's Source / Target combos (any actor) and Swap button.
void drawMorphSides(Document& doc, AssetCache& assets, StatusMessage& status);

}  // namespace animorph
