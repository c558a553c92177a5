#include "core/export/project_frames.h"

#include "core/project/animorphosis_project.h"
#include "core/project/asset_cache.h"
#include "core/poly/polygonizer.h"
#include "core/scene/animorphosis_preview_source.h"
#include "core/scene/visible_surface.h"
#include "core/util/job_progress.h"

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
    out.compiler_ = std::make_shared<SharedGenericCompiler>(out.generic_);
    out.timing_ = animorphosisTiming(p);
  } else {
    return Error{"the project has no morph or animorphosis to bake (Create > Morph... or Create > Animorphosis... "
                 "makes one)"};
  }
  return out;
}

const std::vector<std::string>& ProjectFrames::notes() const {
  static const std::vector<std::string> none;
  return morph_ ? morph_->notes : none;
}

MorphStage ProjectFrames::stageAt(int frame) const {
  if (!morph_) return MorphStage::Morph;
  double u = 0.0;
  return morphStageAt(morph_->setup, morph_->timeline, timeline_.frameToSec(frame), u);
}

Result<BakedFrame> ProjectFrames::frame(int frame, const FrameBakeSettings& s) const {
  const double timeSec = timeline_.frameToSec(frame);
  const auto cancelled = [&] { return s.cancel && s.cancel->load(); };
  BakedFrame out;
  if (morph_) {
    auto fr = [&]() -> Result<MorphFrame> {
      if (s.implicitStage && stageAt(frame) == MorphStage::Morph) return s.implicitStage(*morph_, timeSec, s.resolution);
      MorphFrameSettings fs;
      fs.resolution = s.resolution;
      fs.threads = s.threads;
      fs.cancel = s.cancel;
      fs.colors = s.colors;
      return evaluateMorphFrame(*morph_, timeSec, fs);
    }();
    if (!fr) return Error{fr.error()};
    if (fr->cancelled || cancelled()) return jobCancelled();
    out.stage = fr->stage;
    out.coreTriangles = fr->coreTriangles;
    if (s.measure) out.measure = measureFrame(frame, fr->mesh, nullptr, fr->coreTriangles);
    if (fr->coreTriangles == 0) out.mesh = std::move(fr->mesh);
    else if (!s.keepInnerShell) out.mesh = visibleSurface(*morph_, *fr);
    else {
      if (s.measure) out.visible = visibleSurface(*morph_, *fr);
      out.mesh = std::move(fr->mesh);
    }
    return out;
  }
  PolygonizeSettings ps;
  ps.resolution = s.resolution;
  ps.threads = s.threads;
  ps.cancel = s.cancel;
  ps.colors = s.colors;  // the primitives' colours as vertex colours (docs/export.md)
  auto r = polygonize(animorphosisProgram(frame), ps);
  if (!r) return Error{r.error()};
  if (r->cancelled || cancelled()) return jobCancelled();
  out.mesh = std::move(r->mesh);
  return out;
}

FrameLevelSet ProjectFrames::levelSet(int frame, int resolution, const std::atomic<bool>* cancel, int threads,
                                      bool colors) const {
  const double timeSec = timeline_.frameToSec(frame);
  return morph_ ? morphFrameLevelSet(*morph_, timeSec, resolution, threads, cancel, colors)
                : fieldLevelSet(animorphosisProgram(frame), resolution, threads, cancel, colors);
}

FieldProgram ProjectFrames::animorphosisProgram(int frame) const {
  FieldProgram program;
  compiler_->compile(timing_, timeline_.frameToSec(frame), program);
  return program;
}

}  // namespace animorph
