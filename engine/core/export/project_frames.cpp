#include "core/export/project_frames.h"

#include "core/animorphosis/evaluate_generic.h"
#include "core/project/animorphosis_project.h"
#include "core/project/asset_cache.h"
#include "core/poly/polygonizer.h"
#include "core/util/job_progress.h"
#include "core/scene/visible_surface.h"

namespace animorph {

Result<ProjectFrames> ProjectFrames::prepare(const Project& p, const std::string& baseDir) {
  ProjectFrames out;
  out.timeline_ = p.timeline;
  if (p.morph.enabled()) {
    AssetCache assets;  // this thread's own: the editor's cache stays on the UI thread
    auto rt = prepareMorph(p, baseDir, assets);
    if (!rt) return Error{rt.error()};
    out.morph_ = *rt;
  } else if (p.animorphosis.enabled()) {
    auto c = projectGenericTree(p);
    if (!c) return Error{c.error()};
    out.generic_ = std::make_shared<const GenericTree>(std::move(*c));
    out.timing_ = animorphosisTiming(p);
  } else {
    return Error{"the project has no morph or animorphosis to bake (Create > Morph... or Create > Animorphosis... "
                 "makes one)"};
  }
  return out;
}

Result<TriangleMesh> ProjectFrames::mesh(int frame, int resolution, const std::atomic<bool>* cancel) const {
  const double timeSec = timeline_.frameToSec(frame);
  if (morph_) {
    MorphFrameSettings fs;
    fs.resolution = resolution;
    fs.cancel = cancel;
    auto fr = evaluateMorphFrame(*morph_, timeSec, fs);
    if (!fr) return Error{fr.error()};
    if (fr->cancelled || (cancel && cancel->load())) return jobCancelled();
    // The collapse and expansion carry the stand-in core as a second closed shell inside the
    // mesh: the file gets what is seen, the boundary of their union.
    if (fr->coreTriangles > 0) return visibleSurface(*morph_, *fr);
    return std::move(fr->mesh);
  }
  PolygonizeSettings ps;
  ps.resolution = resolution;
  ps.cancel = cancel;
  ps.colors = true;  // the primitives' colours as vertex colours (docs/export.md)
  auto r = polygonize(compileGeneric(*generic_, timing_, timeSec), ps);
  if (!r) return Error{r.error()};
  if (r->cancelled || (cancel && cancel->load())) return jobCancelled();
  return std::move(r->mesh);
}

FrameLevelSet ProjectFrames::levelSet(int frame, int resolution, const std::atomic<bool>* cancel) const {
  const double timeSec = timeline_.frameToSec(frame);
  return morph_ ? morphFrameLevelSet(*morph_, timeSec, resolution, 0, cancel)
                : fieldLevelSet(compileGeneric(*generic_, timing_, timeSec), resolution, 0, cancel);
}

}  // namespace animorph
