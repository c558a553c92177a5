#include "core/scene/animorphosis_scene.h"

#include <algorithm>
#include <cstdio>

#include "core/animorphosis/evaluate_generic.h"
#include "core/project/animorphosis_project.h"

namespace animorph {

std::shared_ptr<const GenericTree> AnimorphosisCache::get(const Project& project, const void* owner,
                                                          uint64_t revision) {
  if (!project.animorphosis.enabled()) {
    tree_.reset();
    snapshot_.reset();
    compiler_.reset();
    source_.reset();
    error_.clear();
    owner_ = nullptr;
    return nullptr;
  }
  if (owner == owner_ && revision == revision_ && (tree_ || !error_.empty())) return tree_;
  owner_ = owner;
  revision_ = revision;
  snapshot_.reset();
  source_.reset();
  auto c = projectGenericTree(project);
  if (c) {
    tree_ = std::make_shared<const GenericTree>(std::move(*c));
    compiler_ = std::make_shared<SharedGenericCompiler>(tree_);
    timing_ = animorphosisTiming(project);
    error_.clear();
  } else {
    tree_.reset();
    compiler_.reset();
    error_ = c.error();
  }
  return tree_;
}

std::shared_ptr<const BlobTree> AnimorphosisCache::snapshot(const Project& /*the one get() had*/, double timeSec) {
  if (!tree_) return nullptr;
  if (snapshot_ && snapshotTimeSec_ == timeSec) return snapshot_;
  // Rewritten in place when nobody else holds the previous snapshot (no allocation while scrubbing).
  if (!snapshot_ || snapshot_.use_count() > 1) snapshot_ = std::make_shared<BlobTree>();
  updateGenericSnapshot(*tree_, timing_, timeSec, *snapshot_);
  snapshotTimeSec_ = timeSec;
  return snapshot_;
}

std::shared_ptr<const PreviewSource> AnimorphosisCache::previewSource(const Project& /*the one get() had*/,
                                                                      double timeSec) {
  if (!compiler_) return nullptr;
  if (!source_ || sourceTimeSec_ != timeSec) {
    source_ = animorphosisPreviewSource(compiler_, timing_, timeSec);
    sourceTimeSec_ = timeSec;
  }
  return source_;
}

namespace {

void removeActorDraws(SceneFrame& frame, const std::string& actorId) {
  std::erase_if(frame.blobs, [&](const BlobDraw& d) { return d.actorId == actorId; });
  frame.blobGuides.dropIf([&](const std::string& id) { return id == actorId; });
}

}  // namespace

AnimorphosisSceneInfo applyAnimorphosis(SceneFrame& frame, const Project& project, AnimorphosisCache& cache,
                                        const void* owner, uint64_t revision, bool ghosts) {
  AnimorphosisSceneInfo info;
  auto c = cache.get(project, owner, revision);
  if (!c) {
    if (project.animorphosis.enabled()) info.error = cache.error();
    return info;
  }
  const AnimorphosisSetup& m = project.animorphosis;
  const Actor* source = project.findActor(m.sourceActorId);
  const Actor* target = project.findActor(m.targetActorId);
  const double t = frame.timeSec;
  info.u = (t - m.startSec) / (m.endSec - m.startSec);
  info.s = evaluateS(m.globalS, info.u);
  if (t < m.startSec) {
    info.stage = AnimorphosisStage::Source;
    removeActorDraws(frame, m.targetActorId);
    return info;
  }
  if (t > m.endSec) {
    info.stage = AnimorphosisStage::Target;
    removeActorDraws(frame, m.sourceActorId);
    return info;
  }
  info.stage = AnimorphosisStage::Morph;
  auto shown = [&](const std::string& id) {
    return std::any_of(frame.blobs.begin(), frame.blobs.end(), [&](const BlobDraw& d) { return d.actorId == id; });
  };
  const bool anyShown = shown(m.sourceActorId) || shown(m.targetActorId);
  std::vector<BlobDraw> ghostDraws;
  if (ghosts)
    for (const BlobDraw& d : frame.blobs)
      if (d.actorId == m.sourceActorId || d.actorId == m.targetActorId) {
        BlobDraw g = d;
        g.previewKey = d.actorId + "#ghost";
        g.opacity = kGhostOpacity;
        g.tint = d.actorId == m.sourceActorId ? kGhostSourceTint : kGhostTargetTint;
        ghostDraws.push_back(std::move(g));
      }
  removeActorDraws(frame, m.sourceActorId);
  removeActorDraws(frame, m.targetActorId);
  if (!anyShown) return info;
  BlobDraw d;
  d.actorId = m.sourceActorId;
  d.model = blendedTransform(source->transform, target->transform, float(info.s)).matrix();
  d.treeTimeSec = 0.0;
  d.source = cache.previewSource(project, t);
  d.snapshot = [&cache, &project, t] { return cache.snapshot(project, t); };
  frame.blobs.push_back(std::move(d));
  for (BlobDraw& g : ghostDraws) frame.blobs.push_back(std::move(g));
  return info;
}

std::string describeAnimorphosis(const AnimorphosisSceneInfo& info) {
  if (!info.error.empty()) return info.error;
  switch (info.stage) {
    case AnimorphosisStage::None: return {};
    case AnimorphosisStage::Source: return "animorphosis: source";
    case AnimorphosisStage::Target: return "animorphosis: target";
    case AnimorphosisStage::Morph: break;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "animorphosis u=%.2f s=%.2f", info.u, info.s);
  return buf;
}

}  // namespace animorph
