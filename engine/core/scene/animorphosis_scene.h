#pragma once
// Showing a project's animorphosis in an evaluated scene: before its interval
// the source actor alone, after it the target alone, in between the generic
// tree C(t) in their place, as one BlobTree draw whose preview source compiles
// C(t) straight into its program on the preview worker
// (scene/animorphosis_preview_source.h); the snapshot of C at t as a BlobTree is
// built only for what asks for one.
#include <memory>
#include <string>

#include "core/animorphosis/generic_tree.h"
#include "core/project/project.h"
#include "core/scene/animorphosis_preview_source.h"
#include "core/scene/scene_frame.h"

namespace animorph {

enum class AnimorphosisStage { None, Source, Morph, Target };

struct AnimorphosisSceneInfo {
  AnimorphosisStage stage = AnimorphosisStage::None;
  double u = 0.0;      // (t - t0) / (t1 - t0), not clamped
  double s = 0.0;      // the global s(u)
  std::string error;   // C could not be built (the actors are shown as they are)
};

// Keeps the generic tree C of one document state (built again only when the
// project changes: its revision or the document itself) with its compiler, its
// timing, the last preview source and the last snapshot of C(t).
class AnimorphosisCache {
 public:
  // C for project at revision, or null (no animorphosis, or building it
  // failed: error() says why).
  std::shared_ptr<const GenericTree> get(const Project& project, const void* owner, uint64_t revision);
  // C(timeSec) of the tree get() returned last, as a BlobTree of constant
  // tracks; the same pointer while neither C nor the time change. project is the
  // one get() was given (its timing, kept by get(), is used).
  std::shared_ptr<const BlobTree> snapshot(const Project& project, double timeSec);
  // C(timeSec) of the same tree as a preview source (compiled when polygonised); the same
  // pointer while neither C nor the time change. project as for snapshot().
  std::shared_ptr<const PreviewSource> previewSource(const Project& project, double timeSec);
  const std::string& error() const { return error_; }
  // The compiler of the tree get() returned last (its refill counters), or null.
  std::shared_ptr<const SharedGenericCompiler> compiler() const { return compiler_; }

 private:
  std::shared_ptr<const GenericTree> tree_;
  const void* owner_ = nullptr;
  uint64_t revision_ = 0;
  std::string error_;
  std::shared_ptr<BlobTree> snapshot_;
  double snapshotTimeSec_ = 0.0;
  std::shared_ptr<SharedGenericCompiler> compiler_;
  std::shared_ptr<const PreviewSource> source_;
  double sourceTimeSec_ = 0.0;
  // The project's timing when get() built C: its clip lengths walk both actors' trees (a few ms for
  // the demo), too much to do again for every scrubbed time (snapshot, previewSource).
  AnimorphosisTiming timing_;
};

// Replaces the source and target BlobTree draws (and their skeleton guides)
// of frame by what the animorphosis shows at frame.timeSec: the source before
// the interval, the target after it, C(t) within it, drawn under the source
// actor's id with the actors' transforms interpolated by the global s (T and S
// linearly, R by slerp). Hidden actors stay hidden; with neither visible
// nothing is added. ghosts (the editor's preview when the setup's showGhosts
// is on): within the interval the visible source and target are kept too, as
// ghosts (their own draws at kGhostOpacity, previewKey "id#ghost"), tinted so
// they cannot be taken for C(t): the source blue, the target orange.
inline constexpr float kGhostOpacity = 0.3f;
inline constexpr glm::vec3 kGhostSourceTint{0.15f, 0.25f, 1.00f};  // deeper than the clay tone of C
inline constexpr glm::vec3 kGhostTargetTint{1.00f, 0.55f, 0.18f};
AnimorphosisSceneInfo applyAnimorphosis(SceneFrame& frame, const Project& project, AnimorphosisCache& cache,
                                        const void* owner, uint64_t revision, bool ghosts = false);

// "animorphosis u=0.42", "animorphosis: source", "animorphosis: target", or the error.
std::string describeAnimorphosis(const AnimorphosisSceneInfo& info);

}  // namespace animorph
