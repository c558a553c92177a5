#include "core/export/frame_stage.h"

#include "core/scene/morph_runtime.h"

namespace animorph {

std::string frameStageLabel(const Project& p, int frame) {
  if (!p.morph.enabled()) return p.animorphosis.enabled() ? "animorphosis" : "";
  MorphSetup setup = p.morph;
  auto isTree = [&](const std::string& id) {
    const Actor* a = p.findActor(id);
    return a && a->kind == ActorKind::BlobTree;
  };
  if (isTree(setup.sourceActorId)) setup.markers.a = setup.markers.b;
  if (isTree(setup.targetActorId)) setup.markers.d = setup.markers.c;
  double u = 0.0;
  switch (morphStageAt(setup, p.timeline, p.timeline.frameToSec(frame), u)) {
    case MorphStage::Source: return "before A";
    case MorphStage::Collapse: return "A..B";
    case MorphStage::Morph: return "B..C";
    case MorphStage::Expand: return "C..D";
    case MorphStage::Target: break;
  }
  return "after D";
}

std::vector<FrameStageSpan> frameStageSpans(const Project& p, int first, int last) {
  std::vector<FrameStageSpan> spans;
  for (int f = first; f <= last; ++f) {
    std::string label = frameStageLabel(p, f);
    if (!spans.empty() && spans.back().label == label) spans.back().last = f;
    else spans.push_back({f, f, std::move(label)});
  }
  return spans;
}

}  // namespace animorph
