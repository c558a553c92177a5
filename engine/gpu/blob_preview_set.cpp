#include "blob_preview_set.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "shared_constants.h"

namespace animorph::gpu {

Mesh meshFromTriangles(const TriangleMesh& tm, const std::string& name) {
  Mesh m;
  m.name = name;
  m.positions = tm.positions;
  m.normals = tm.normals;
  m.indices = tm.indices;
  return m;
}

BlobPreviewSet::~BlobPreviewSet() {
  entries_.clear();  // joins the workers
  retired_.clear();
}

void BlobPreviewSet::update(const Project& project, const SceneFrame& frame, const BlobPreviewSettings& settings) {
  // Forget actors that are gone or no longer BlobTrees.
  for (auto it = entries_.begin(); it != entries_.end();) {
    const Actor* a = project.findActor(it->first);
    if (!a || a->kind != ActorKind::BlobTree) {
      if (it->second.mesh) retired_.emplace_back(frame_, std::move(it->second.mesh));
      it = entries_.erase(it);
    } else {
      ++it;
    }
  }
  for (const BlobDraw& d : frame.blobs) {
    const Actor* a = project.findActor(d.actorId);
    if (!a || a->kind != ActorKind::BlobTree) continue;
    Entry& e = entries_[d.actorId];
    if (!e.worker) e.worker = std::make_unique<PreviewPolygonizer>(settings.threads);
    bool treeChanged = !e.submittedTree || !(*e.submittedTree == a->blobTree);
    if (treeChanged || e.submittedTimeSec != d.treeTimeSec || e.submittedCoarse != settings.coarseResolution ||
        e.submittedFine != settings.fineResolution) {
      if (treeChanged) e.submittedTree = std::make_shared<const BlobTree>(a->blobTree);
      e.submittedTimeSec = d.treeTimeSec;
      e.submittedCoarse = settings.coarseResolution;
      e.submittedFine = settings.fineResolution;
      PreviewRequest r;
      r.tree = e.submittedTree;
      r.timeSec = d.treeTimeSec;
      r.coarseResolution = settings.coarseResolution;
      r.fineResolution = settings.fineResolution;
      e.worker->submit(std::move(r));
    }
    uploadNew(e);
  }
}

void BlobPreviewSet::uploadNew(Entry& e) {
  if (!e.worker || e.worker->latestSerial() == e.uploadedSerial) return;
  auto r = e.worker->latest();
  if (!r) return;
  e.uploadedSerial = r->serial;
  e.result = r;
  if (e.mesh) retired_.emplace_back(frame_, std::move(e.mesh));
  if (!r->error.empty()) {
    lastError_ = r->error;
    return;
  }
  if (r->mesh.positions.empty()) return;  // nothing inside: draw nothing
  auto up = GpuMesh::upload(ctx_, meshFromTriangles(r->mesh, "blob preview"));
  if (up) e.mesh = std::move(*up);
  else lastError_ = up.error();
}

const GpuMesh* BlobPreviewSet::mesh(const std::string& actorId) const {
  auto it = entries_.find(actorId);
  return it == entries_.end() ? nullptr : it->second.mesh.get();
}

std::shared_ptr<const PreviewResult> BlobPreviewSet::result(const std::string& actorId) const {
  auto it = entries_.find(actorId);
  return it == entries_.end() ? nullptr : it->second.result;
}

bool BlobPreviewSet::busy() const {
  for (const auto& [id, e] : entries_)
    if (e.worker && e.worker->busy()) return true;
  return false;
}

bool BlobPreviewSet::waitIdle(double timeoutSec) {
  auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSec);
  bool idle = true;
  for (auto& [id, e] : entries_) {
    double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (e.worker && !e.worker->waitIdle(std::max(0.0, left))) idle = false;
    uploadNew(e);
  }
  return idle;
}

void BlobPreviewSet::endFrame() {
  ++frame_;
  std::erase_if(retired_, [&](const auto& r) { return frame_ - r.first > kFramesInFlight + 1; });
}

}  // namespace animorph::gpu
