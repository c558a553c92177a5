#include "gpu/render/standin_overlay.h"

namespace animorph::gpu {

void addStandinOverlay(const std::vector<StandinGuides>& guides, const std::string& selectedActorId,
                       int selectedSegment, LineBatch& overlay) {
  const uint32_t plain = packRgba({0.85f, 0.45f, 0.95f, 0.75f});
  const uint32_t actorSel = packRgba({0.95f, 0.65f, 1.0f, 1.0f});
  const uint32_t segSel = packRgba({1.0f, 0.85f, 0.2f, 1.0f});
  for (const StandinGuides& g : guides) {
    const bool actor = g.actorId == selectedActorId;
    for (const StandinGuideSegment& s : g.segments) {
      const bool sel = actor && s.index == selectedSegment;
      const uint32_t c = sel ? segSel : actor ? actorSel : plain;
      for (const StandinGuideLine& l : standinCapsuleLines(s, sel ? 32 : 16)) overlay.line(l.a, l.b, c);
    }
  }
}

}  // namespace animorph::gpu
