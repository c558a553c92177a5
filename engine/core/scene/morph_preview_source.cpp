#include "core/scene/morph_preview_source.h"

#include "core/scene/standin_core.h"

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
    return PreviewField{std::move(f.program), f.bounds, f.noiseAmplitude, rt_->setup.noiseFrequency, f.colorProgram,
                        std::nullopt, nullptr};
  }

 private:
  std::shared_ptr<const MorphRuntime> rt_;
  double timeSec_;
  double progress_;
};

class StandinCoreSource final : public PreviewSource {
 public:
  StandinCoreSource(std::shared_ptr<const MorphRuntime> rt, double timeSec, bool expand, double u)
      : rt_(std::move(rt)), timeSec_(timeSec), expand_(expand), u_(u) {}
  bool sameAs(const PreviewSource& other) const override {
    auto* o = dynamic_cast<const StandinCoreSource*>(&other);
    return o && o->rt_ == rt_ && o->timeSec_ == timeSec_ && o->expand_ == expand_ && o->u_ == u_;
  }
  // Polygonised by the morph runtime too, without temporal coherence.
  Result<PolygonizeResult> polygonize(int resolution, int threads, const std::atomic<bool>* cancel,
                                      PolygonizeHistory*) const override {
    MorphFrame fr;
    fr.timeSec = timeSec_;
    fr.stage = expand_ ? MorphStage::Expand : MorphStage::Collapse;
    fr.progress = u_;
    MorphFrameSettings fs;
    fs.resolution = resolution;
    fs.threads = threads;
    fs.cancel = cancel;
    if (Status s = appendStandinCore(*rt_, fr, fs); !s) return Error{s.error()};
    PolygonizeResult r;
    r.mesh = std::move(fr.mesh);
    r.stats = fr.polygonize;
    r.cancelled = fr.cancelled;
    return r;
  }
  Result<PreviewField> field(int) const override {
    std::optional<MorphImplicitField> f = standinCoreField(*rt_, timeSec_, expand_, u_);
    if (!f) return Error{"the stand-in core has melted away at this time"};
    return PreviewField{std::move(f->program), f->bounds, f->noiseAmplitude, rt_->setup.noiseFrequency,
                        f->colorProgram, std::nullopt, nullptr};
  }

 private:
  std::shared_ptr<const MorphRuntime> rt_;
  double timeSec_;
  bool expand_;
  double u_;
};

}  // namespace

std::shared_ptr<const PreviewSource> standinCorePreviewSource(std::shared_ptr<const MorphRuntime> rt, double timeSec,
                                                              bool expand, double u) {
  return std::make_shared<const StandinCoreSource>(std::move(rt), timeSec, expand, u);
}

std::shared_ptr<const PreviewSource> morphPreviewSource(std::shared_ptr<const MorphRuntime> rt, double timeSec,
                                                        double progress) {
  return std::make_shared<const MorphStageSource>(std::move(rt), timeSec, progress);
}

}  // namespace animorph
