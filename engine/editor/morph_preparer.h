#pragma once
// The editor's morph preparation, off the UI thread. prepareMorph (scene/morph_runtime.h) loads
// the characters and binds every vertex to its stand-in: tens to hundreds of milliseconds on a
// real character, too long for a frame. MorphPreparer runs it as a BackgroundJob on a copy of the
// project and of the asset cache whenever the document's revision changes, and until the job
// finishes keeps handing out the previous runtime of the same document (the old morph stays on
// screen instead of the frame freezing). A job is never restarted mid-way: when the project
// changes again while one runs (a drag edits the morph every frame), the next job starts when it
// finishes, with the project as it is then. MorphCache (scene/morph_scene.h) is the synchronous
// form for the command line.
#include <cstdint>
#include <memory>
#include <string>

#include "core/project/asset_cache.h"
#include "core/project/project.h"
#include "core/scene/morph_runtime.h"
#include "core/util/background_job.h"

namespace animorph {

class MorphPreparer {
 public:
  MorphPreparer() = default;
  ~MorphPreparer();  // cancels and waits for a running job
  MorphPreparer(const MorphPreparer&) = delete;
  MorphPreparer& operator=(const MorphPreparer&) = delete;

  // Call once per UI frame. Returns the runtime to show for project at revision (owner: the
  // Document, so that another document's runtime is never shown): the prepared one when it is
  // current, else the previous one of the same owner while a job prepares the current one, else
  // null (no morph, a failed preparation: error(), or the first preparation of a document is
  // still running: preparing()). A finished job's characters are added to assets.
  std::shared_ptr<const MorphRuntime> update(const Project& project, const std::string& baseDir, AssetCache& assets,
                                             const void* owner, uint64_t revision);

  // A job is running (what update() returned may be out of date).
  bool preparing() const { return job_ != nullptr; }
  // The last preparation's error (empty when it succeeded).
  const std::string& error() const { return error_; }
  // Blocks until no job runs, then brings the runtime up to date (automation, tests).
  std::shared_ptr<const MorphRuntime> wait(const Project& project, const std::string& baseDir, AssetCache& assets,
                                           const void* owner, uint64_t revision);

 private:
  void start(const Project& project, const std::string& baseDir, const AssetCache& assets, const void* owner,
             uint64_t revision);
  void collect(AssetCache& assets);

  std::shared_ptr<const MorphRuntime> runtime_;  // the last prepared runtime
  const void* owner_ = nullptr;                  // whose runtime_ is
  uint64_t revision_ = 0;                        // the revision runtime_ / error_ are of
  bool current_ = false;                         // runtime_ / error_ are of (owner_, revision_)
  std::string error_;

  // The running job and what it works on (it owns copies; the UI thread touches them only once
  // the job has finished).
  struct Work {
    Project project;
    std::string baseDir;
    AssetCache assets;
    std::shared_ptr<const MorphRuntime> previous;
    Result<std::shared_ptr<const MorphRuntime>> result = Error{"not run"};
  };
  std::shared_ptr<Work> work_;
  const void* jobOwner_ = nullptr;
  uint64_t jobRevision_ = 0;
  std::unique_ptr<BackgroundJob> job_;
};

}  // namespace animorph
