#pragma once
// The frames a project bakes into: its morph (prepared once: characters loaded, vertices bound)
// or, when it has only an animorphosis, its C(t). Shared by the export (export/export_project.h)
// and the editor's playblast, which run it on a background job's thread on a copy of the project.
#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "core/animorphosis/animorphosis_timing.h"
#include "core/animorphosis/generic_tree.h"
#include "core/export/frame_volume.h"
#include "core/project/project.h"
#include "core/scene/morph_runtime.h"
#include "core/poly/mesh.h"
#include "core/util/result.h"

namespace animorph {

class ProjectFrames {
 public:
  // Errors name the project element and the reason ("export: ..." is the caller's prefix); a
  // project with neither a morph nor an animorphosis is an error too.
  static Result<ProjectFrames> prepare(const Project& p, const std::string& baseDir);

  // Scene frame f as a mesh (world space for a morph, the trees' own space for an animorphosis),
  // polygonised at resolution cells. A cancel seen during the polygonisation comes back as
  // jobCancelled() (util/job_progress.h).
  Result<TriangleMesh> mesh(int frame, int resolution, const std::atomic<bool>* cancel) const;
  // Frame f's implicit field as a level set; none for a skinned-mesh frame of a morph.
  FrameLevelSet levelSet(int frame, int resolution, const std::atomic<bool>* cancel) const;

 private:
  Timeline timeline_;
  std::shared_ptr<const MorphRuntime> morph_;  // or else the animorphosis:
  std::shared_ptr<const GenericTree> generic_;
  AnimorphosisTiming timing_;
};

}  // namespace animorph
