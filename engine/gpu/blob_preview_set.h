#pragma once
// The polygonised previews of a project's BlobTree actors, on the GPU. Per
// actor: a PreviewPolygonizer (worker thread) fed with the actor's tree and
// time every frame, and the GPU mesh of its newest result, uploaded when a new
// result arrives. Replaced meshes are freed once no frame in flight can use
// them. The frame loop never waits for a polygoniser.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "context.h"
#include "doc/project.h"
#include "gpu_mesh.h"
#include "poly/preview_polygonizer.h"
#include "scene/scene_frame.h"

namespace animorph::gpu {

struct BlobPreviewSettings {
  int coarseResolution = 48;  // first answer while scrubbing or editing
  int fineResolution = 128;   // refined answer once nothing changes
  int threads = 0;            // polygoniser threads per actor run (0: all)
};

class BlobPreviewSet {
 public:
  explicit BlobPreviewSet(Context& ctx) : ctx_(ctx) {}
  ~BlobPreviewSet();
  BlobPreviewSet(const BlobPreviewSet&) = delete;
  BlobPreviewSet& operator=(const BlobPreviewSet&) = delete;

  // Once per frame: submits every BlobTree actor of frame (its tree from
  // project, at its tree time), uploads new results, forgets actors gone from
  // the project. Upload errors go to lastError().
  void update(const Project& project, const SceneFrame& frame, const BlobPreviewSettings& settings);
  // The actor's newest uploaded mesh (null before its first result or for an empty shape).
  const GpuMesh* mesh(const std::string& actorId) const;
  // The newest result of the actor (CPU mesh, stats, error), or null.
  std::shared_ptr<const PreviewResult> result(const std::string& actorId) const;
  // True while some actor's preview is being computed.
  bool busy() const;
  // Waits until every actor's worker is idle, then uploads (tests, screenshots). Returns idle.
  bool waitIdle(double timeoutSec);
  // Call once per frame after submitting: frees meshes replaced kFramesInFlight + 1 frames ago.
  void endFrame();
  const std::string& lastError() const { return lastError_; }

 private:
  struct Entry {
    std::unique_ptr<PreviewPolygonizer> worker;
    std::shared_ptr<const BlobTree> submittedTree;
    double submittedTimeSec = -1.0;
    int submittedCoarse = 0, submittedFine = 0;
    uint64_t uploadedSerial = 0;
    std::shared_ptr<const PreviewResult> result;
    std::unique_ptr<GpuMesh> mesh;
  };
  void uploadNew(Entry& e);

  Context& ctx_;
  std::map<std::string, Entry> entries_;
  std::vector<std::pair<uint64_t, std::unique_ptr<GpuMesh>>> retired_;  // (frame retired, mesh)
  uint64_t frame_ = 0;
  std::string lastError_;
};

// The GPU-side Mesh of a polygonised surface (positions, normals, triangles; no skin).
Mesh meshFromTriangles(const TriangleMesh& tm, const std::string& name);

}  // namespace animorph::gpu
