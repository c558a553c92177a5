#include "editor/morph_preparer.h"

namespace animorph {

MorphPreparer::~MorphPreparer() {
  if (job_) job_->cancel();
  job_.reset();  // waits for the work to return
}

void MorphPreparer::start(const Project& project, const std::string& baseDir, const AssetCache& assets,
                          const void* owner, uint64_t revision) {
  work_ = std::make_shared<Work>();
  work_->project = project;
  work_->baseDir = baseDir;
  work_->assets = assets;  // shares the loaded characters (immutable); new loads stay in the copy
  work_->previous = owner == owner_ ? runtime_ : nullptr;
  jobOwner_ = owner;
  jobRevision_ = revision;
  std::shared_ptr<Work> w = work_;
  job_ = std::make_unique<BackgroundJob>("Prepare morph", [w](JobProgress& progress) -> Status {
    progress.setStage("Binding vertices to the stand-ins");
    w->result = prepareMorph(w->project, w->baseDir, w->assets, w->previous.get());
    return Status::success();
  });
}

void MorphPreparer::collect(AssetCache& assets) {
  job_.reset();  // finished: returns at once
  Work& w = *work_;
  if (jobOwner_ != owner_) runtime_.reset();
  owner_ = jobOwner_;
  revision_ = jobRevision_;
  current_ = true;
  if (w.result) {
    runtime_ = *w.result;
    error_.clear();
  } else {
    runtime_.reset();
    error_ = w.result.error();
  }
  // Characters the job loaded: keep them, so the next frame does not load them again.
  for (const auto& [path, entry] : w.assets.entries())
    if (!assets.contains(path)) assets.insert(path, entry);
  work_.reset();
}

std::shared_ptr<const MorphRuntime> MorphPreparer::update(const Project& project, const std::string& baseDir,
                                                          AssetCache& assets, const void* owner, uint64_t revision) {
  if (job_ && job_->finished()) collect(assets);
  if (!project.morph.enabled()) {
    // Nothing to show; a running job finishes on its own and is dropped when collected.
    if (!job_) {
      runtime_.reset();
      error_.clear();
      owner_ = owner;
      current_ = false;
    }
    return nullptr;
  }
  const bool upToDate = current_ && owner == owner_ && revision == revision_;
  if (!upToDate && !job_) start(project, baseDir, assets, owner, revision);
  if (owner != owner_) return nullptr;  // never another document's morph
  return runtime_;
}

std::shared_ptr<const MorphRuntime> MorphPreparer::wait(const Project& project, const std::string& baseDir,
                                                        AssetCache& assets, const void* owner, uint64_t revision) {
  for (;;) {
    update(project, baseDir, assets, owner, revision);
    if (!job_) return update(project, baseDir, assets, owner, revision);
    job_->wait();
  }
}

}  // namespace animorph
