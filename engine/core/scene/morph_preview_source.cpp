#include "scene/morph_preview_source.h"

namespace animorph {

namespace {

class MorphStageSource final : public PreviewSource {
 public:
  MorphStageSource(std::shared_ptr<const MorphRuntime> rt, double timeSec, double progress)
      : rt_(std::move(rt)), timeSec_(timeSec), progress_(progress) {}
  bool sameAs(const PreviewSource& other) const override {
    auto* o = dynamic_cast<const MorphStageSource*>(&other);
    return o && o->rt_ == rt_ && o->timeSec_ == timeSec_ && o->progress_ == progress_;
  }
  // The morph's field is polygonised by the morph runtime, without temporal coherence.
  Result<PolygonizeResult> polygonize(int resolution, int threads, const std::atomic<bool>* cancel,
                                      PolygonizeHistory*) const override {
    MorphFrameSettings fs;
    fs.resolution = resolution;
    fs.threads = threads;
    fs.cancel = cancel;
    auto fr = progress_ >= 0.0 ? evaluateMorphImplicit(*rt_, timeSec_, progress_, fs) : evaluateMorphFrame(*rt_, timeSec_, fs);
    if (!fr) return Error{fr.error()};
    PolygonizeResult r;
    r.mesh = std::move(fr->mesh);
    r.stats = fr->polygonize;
    r.cancelled = fr->cancelled;
    return r;
  }
  Result<PreviewField> field(int resolution) const override {
    MorphImplicitField f = morphImplicitField(*rt_, timeSec_, resolution, progress_);
    // The noise displaces the polygonised mesh (on the GPU: a pass after the normals).
    return PreviewField{std::move(f.program), f.bounds, f.noiseAmplitude, rt_->setup.noiseFrequency};
  }

 private:
  std::shared_ptr<const MorphRuntime> rt_;
  double timeSec_;
  double progress_;
};

}  // namespace

std::shared_ptr<const PreviewSource> morphPreviewSource(std::shared_ptr<const MorphRuntime> rt, double timeSec,
                                                        double progress) {
  return std::make_shared<const MorphStageSource>(std::move(rt), timeSec, progress);
}

}  // namespace animorph
