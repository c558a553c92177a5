#include "gpu/polygonizer/blob_preview_set.h"

#include <algorithm>
#include <chrono>

#include "shared_constants.h"

namespace animorph::gpu {

void BlobPreviewSet::update(const Project& project, const SceneFrame& frame, const BlobPreviewSettings& settings) {
  // Forget actors that are gone or no longer BlobTrees (a ghost's key is "actorId#ghost").
  for (auto it = entries_.begin(); it != entries_.end();) {
    const Actor* a = project.findActor(it->first.substr(0, it->first.find('#')));
    if (!a || a->kind != ActorKind::BlobTree) {
      retired_.emplace_back(frame_, std::move(it->second.preview));
      it = entries_.erase(it);
    } else {
      ++it;
    }
  }
  ImplicitPreviewSettings ps;
  ps.interactiveResolution = settings.coarseResolution;
  ps.refinedResolution = settings.fineResolution;
  ps.threads = settings.threads;
  ps.gpu = settings.gpu;
  ps.settle = settings.settle;
  for (const BlobDraw& d : frame.blobs) {
    const Actor* a = project.findActor(d.actorId);
    if (!a || a->kind != ActorKind::BlobTree) continue;
    Entry& e = entries_[d.key()];
    if (!e.preview) e.preview = std::make_unique<ImplicitPreview>(ctx_);
    if (d.source) {
      // The animorphosis' C(t): its own source, a new pointer when it changes.
      e.submittedTree.reset();
      e.source = d.source;
    } else if (!e.submittedTree || !(*e.submittedTree == a->blobTree) || e.submittedTimeSec != d.treeTimeSec ||
               !e.source) {
      if (!e.submittedTree || !(*e.submittedTree == a->blobTree))
        e.submittedTree = std::make_shared<const BlobTree>(a->blobTree);
      e.submittedTimeSec = d.treeTimeSec;
      e.source = blobTreePreviewSource(e.submittedTree, d.treeTimeSec);
    }
    e.preview->update(e.source, d.treeTimeSec, ps);
  }
}

void BlobPreviewSet::draw(const std::string& actorId, Scene& scene, const glm::mat4& model, const glm::vec4& color,
                          bool selected) const {
  auto it = entries_.find(actorId);
  if (it != entries_.end()) it->second.preview->draw(scene, model, color, selected);
}

std::shared_ptr<const PreviewResult> BlobPreviewSet::result(const std::string& actorId) const {
  auto it = entries_.find(actorId);
  return it == entries_.end() ? nullptr : it->second.preview->cpuResult();
}

ImplicitPreviewStatus BlobPreviewSet::status(const std::string& actorId) const {
  auto it = entries_.find(actorId);
  return it == entries_.end() ? ImplicitPreviewStatus{} : it->second.preview->status();
}

PreviewFieldCounters BlobPreviewSet::fieldCounters(const std::string& actorId) const {
  auto it = entries_.find(actorId);
  return it == entries_.end() ? PreviewFieldCounters{} : it->second.preview->fieldCounters();
}

bool BlobPreviewSet::busy() const {
  for (const auto& [id, e] : entries_)
    if (e.preview->busy()) return true;
  return false;
}

bool BlobPreviewSet::needsFrames() const {
  for (const auto& [id, e] : entries_)
    if (e.preview->needsFrames()) return true;
  return false;
}

bool BlobPreviewSet::waitIdle(double timeoutSec) {
  auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSec);
  bool idle = true;
  for (auto& [id, e] : entries_) {
    double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (!e.preview->waitIdle(std::max(0.0, left))) idle = false;
  }
  return idle;
}

void BlobPreviewSet::clearGpuFailures() {
  for (auto& [id, e] : entries_) e.preview->clearGpuFailure();
}

void BlobPreviewSet::endFrame() {
  ++frame_;
  for (auto& [id, e] : entries_) e.preview->endFrame();
  std::erase_if(retired_, [&](const auto& r) { return frame_ - r.first > kFramesInFlight + 1; });
}

}  // namespace animorph::gpu
