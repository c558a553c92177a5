#pragma once
// The polygonised previews of a project's BlobTree actors: one ImplicitPreview
// per actor (CPU worker or GPU polygoniser, implicit_preview.h), fed with the
// actor's tree and time every frame. The frame loop never waits for a polygoniser.
#include <map>
#include <memory>
#include <string>

#include "gpu/vulkan/context.h"
#include "core/project/project.h"
#include "gpu/polygonizer/implicit_preview.h"
#include "core/scene/scene_frame.h"

namespace animorph::gpu {

struct BlobPreviewSettings {
  int coarseResolution = 96;  // first answer while scrubbing or editing
  int fineResolution = 128;   // refined answer once nothing changes
  int threads = 0;            // polygoniser threads per actor run (0: all)
  bool gpu = false;           // polygonise on the GPU (falls back to the CPU on failure)
  bool settle = false;        // GPU: straight to the fine resolution (screenshots)
};

class BlobPreviewSet {
 public:
  explicit BlobPreviewSet(Context& ctx) : ctx_(ctx) {}
  BlobPreviewSet(const BlobPreviewSet&) = delete;
  BlobPreviewSet& operator=(const BlobPreviewSet&) = delete;

  // Once per frame: submits every BlobTree draw of frame (the draw's own tree
  // when it has one, else the actor's tree from project, at its tree time),
  // forgets actors gone from the project.
  void update(const Project& project, const SceneFrame& frame, const BlobPreviewSettings& settings);
  // Appends the actor's newest mesh to scene (nothing before its first result).
  void draw(const std::string& actorId, Scene& scene, const glm::mat4& model, const glm::vec4& color,
            bool selected) const;
  // The newest CPU result of the actor (mesh, stats, error), or null (none yet, or on the GPU path).
  std::shared_ptr<const PreviewResult> result(const std::string& actorId) const;
  // The actor's preview status (empty for an unknown actor).
  ImplicitPreviewStatus status(const std::string& actorId) const;
  // The actor's GPU field compiles so far (ImplicitPreview::fieldCounters; empty for an unknown actor).
  PreviewFieldCounters fieldCounters(const std::string& actorId) const;
  // True while some actor's preview is being computed.
  bool busy() const;
  // True while some actor's preview moves on only with more frames (ImplicitPreview::needsFrames).
  bool needsFrames() const;
  // Waits until every actor's preview is idle (tests, screenshots). Returns idle.
  bool waitIdle(double timeoutSec);
  // Forgets GPU failures (the user switched devices).
  void clearGpuFailures();
  // Call once per frame after submitting: frees meshes no frame in flight uses.
  void endFrame();

 private:
  struct Entry {
    std::unique_ptr<ImplicitPreview> preview;
    std::shared_ptr<const BlobTree> submittedTree;
    double submittedTimeSec = -1.0;
    std::shared_ptr<const PreviewSource> source;
  };

  Context& ctx_;
  std::map<std::string, Entry> entries_;
  // Previews of removed actors, kept until no frame in flight draws their meshes: (frame, preview).
  std::vector<std::pair<uint64_t, std::unique_ptr<ImplicitPreview>>> retired_;
  uint64_t frame_ = 0;
};

}  // namespace animorph::gpu
