#include "editor/click_selection.h"

namespace animorph {

std::optional<ScenePick> nearerPick(std::optional<ScenePick> a, std::optional<ScenePick> b) {
  if (!a) return b;
  if (!b) return a;
  return b->distance < a->distance ? b : a;
}

Selection selectionAfterClick(const Selection& current, const std::optional<BlobGuidePick>& guide,
                              const std::optional<ScenePick>& hit, bool extend) {
  if (guide) return Selection{guide->actorId, guide->node};
  if (hit) return Selection{hit->actorId, -1};
  return extend ? current : Selection{};
}

}  // namespace animorph
