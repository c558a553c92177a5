#include "core/project/animorphosis_project.h"

#include "core/animorphosis/validate_correspondence.h"
#include "core/project/animation_end_cache.h"

namespace animorph {

namespace {

ClipTiming clipOf(const Actor& a) {
  if (!a.loop) return ClipTiming{a.timeOffsetSec, a.speed, 0.0};
  double end = AnimationEndScope::endSec(a);  // kept per revision inside the editor's scopes
  return ClipTiming{a.timeOffsetSec, a.speed, end > 1e-6 ? end : 0.0};
}

}  // namespace

Status checkAnimorphosis(const Project& p) {
  const AnimorphosisSetup& m = p.animorphosis;
  if (!m.enabled()) return Error{"animorphosis: no source and target actors are set"};
  for (const std::string* id : {&m.sourceActorId, &m.targetActorId}) {
    const char* role = id == &m.sourceActorId ? "source" : "target";
    const Actor* a = p.findActor(*id);
    if (!a) return Error{std::string("animorphosis: ") + role + " actor '" + *id + "' does not exist"};
    if (a->kind != ActorKind::BlobTree)
      return Error{std::string("animorphosis: ") + role + " actor '" + *id + "' is not a BlobTree actor"};
  }
  if (m.sourceActorId == m.targetActorId) return Error{"animorphosis: source and target are the same actor"};
  if (!(m.endSec > m.startSec)) return Error{"animorphosis: the interval ends before it starts"};
  if (Status s = checkSCurve(m.globalS, "animorphosis: global s"); !s) return s;
  Status g = validateCorrespondence(p.findActor(m.sourceActorId)->blobTree, p.findActor(m.targetActorId)->blobTree,
                                    m.graph);
  if (!g) return Error{"animorphosis: " + g.error()};
  return Status::success();
}

CorrespondenceGraph stillValidLinks(const Project& p) {
  const AnimorphosisSetup& m = p.animorphosis;
  const Actor* a = p.findActor(m.sourceActorId);
  const Actor* b = p.findActor(m.targetActorId);
  if (!a || !b) return {};
  CorrespondenceGraph kept;
  if (validateCorrespondence(a->blobTree, b->blobTree, m.graph).ok()) {
    kept.links = m.graph.links;
  } else {
    for (const auto& l : m.graph.links) {
      kept.links.push_back(l);
      if (!validateCorrespondence(a->blobTree, b->blobTree, kept).ok()) kept.links.pop_back();
    }
  }
  // Suggestions are checked when accepted; those whose nodes are gone are dropped.
  for (const auto& l : m.graph.suggestions)
    if (a->blobTree.find(l.nodeA) && b->blobTree.find(l.nodeB)) kept.suggestions.push_back(l);
  return kept;
}

AnimorphosisTiming animorphosisTiming(const Project& p) {
  const AnimorphosisSetup& m = p.animorphosis;
  AnimorphosisTiming t;
  t.startSec = m.startSec;
  t.endSec = m.endSec;
  t.globalS = m.globalS;
  if (const Actor* a = p.findActor(m.sourceActorId)) t.source = clipOf(*a);
  if (const Actor* b = p.findActor(m.targetActorId)) t.target = clipOf(*b);
  return t;
}

Result<GenericTree> projectGenericTree(const Project& p) {
  if (Status s = checkAnimorphosis(p); !s) return Error{s.error()};
  AnimorphosisTiming t = animorphosisTiming(p);
  GenericOptions o;
  o.anchorTimeSecA = t.source.localTime(t.startSec);
  o.anchorTimeSecB = t.target.localTime(t.startSec);
  const AnimorphosisSetup& m = p.animorphosis;
  auto c = buildGenericTree(p.findActor(m.sourceActorId)->blobTree, p.findActor(m.targetActorId)->blobTree, m.graph, o);
  if (!c) return Error{"animorphosis: " + c.error()};
  return c;
}

Transform blendedTransform(const Transform& source, const Transform& target, float s) {
  Transform t;
  t.translation = glm::mix(source.translation, target.translation, s);
  t.rotation = glm::slerp(source.rotation, target.rotation, s);
  t.scale = glm::mix(source.scale, target.scale, s);
  return t;
}

}  // namespace animorph
