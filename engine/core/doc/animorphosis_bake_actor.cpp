#include "core/doc/animorphosis_bake_actor.h"

#include <cstdio>

#include "core/doc/actor_commands.h"
#include "core/project/animorphosis_project.h"
#include "core/util/job_progress.h"

namespace animorph {

Result<BakedActor> bakeAnimorphosisActor(const Project& p, const BakeKeysSettings& settings) {
  auto c = projectGenericTree(p);
  if (!c) return Error{c.error()};
  const AnimorphosisSetup& m = p.animorphosis;
  const Actor& src = *p.findActor(m.sourceActorId);  // checked by projectGenericTree
  const Actor& dst = *p.findActor(m.targetActorId);
  const AnimorphosisTiming timing = animorphosisTiming(p);
  BakedAnimorphosis baked = bakeKeyframes(*c, timing, settings);
  if (baked.cancelled) return jobCancelled();
  BakedActor out;
  out.report = baked.report;
  Actor& a = out.actor;
  a.kind = ActorKind::BlobTree;
  a.id = p.uniqueActorId(src.id + "_to_" + dst.id);
  a.name = p.uniqueActorName(src.name + " -> " + dst.name + " (keys)");
  a.blobTree = std::move(baked.tree);
  a.timeOffsetSec = 0.0;
  a.speed = 1.0;
  a.loop = false;
  a.transform = blendedTransform(src.transform, dst.transform, timing.globalS.evaluate(0.5));  // C at u = 0.5
  return out;
}

std::unique_ptr<Command> addBakedActorCommand(const Project& p, BakedActor baked) {
  std::string base = baked.actor.id;
  if (p.findActor(base)) baked.actor.id = p.uniqueActorId(base);
  return addActorCommand(std::move(baked.actor));
}

std::string describeBakedActor(const BakedActor& baked) {
  const BakeKeysReport& r = baked.report;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "Baked %s: %zu nodes, %zu channels, %zu keys, at most %d on one channel (nA + nB + ns = %d)%s; "
                "largest deviation from the live animorphosis %g%s%s%s",
                baked.actor.name.c_str(), size_t(baked.actor.blobTree.root.subtreeSize()), r.parameters, r.keys,
                r.mostKeys, r.mostKeysBound, r.withinBound ? "" : ", clip loops exceed the bound on some channels",
                r.largestDeviation, r.largestDeviationAt.empty() ? "" : " (", r.largestDeviationAt.c_str(),
                r.largestDeviationAt.empty() ? "" : ")");
  return buf;
}

}  // namespace animorph
