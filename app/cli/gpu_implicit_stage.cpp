#include "app/cli/gpu_implicit_stage.h"

namespace animorph::cli {

Result<std::unique_ptr<GpuImplicitStage>> GpuImplicitStage::create() {
  auto c = gpu::Context::create(gpu::ContextSettings{});
  if (!c) return Error{"no usable Vulkan device: " + c.error()};
  std::unique_ptr<GpuImplicitStage> out(new GpuImplicitStage);
  out->context_ = std::move(*c);
  auto poly = gpu::GpuPolygonizer::create(*out->context_);
  if (!poly) return Error{poly.error()};
  out->polygonizer_ = std::move(*poly);
  return out;
}

uint32_t GpuImplicitStage::validationErrors() const {
  return context_->validationEnabled() ? context_->validationErrorCount() : 0u;
}

ImplicitStagePolygonizer GpuImplicitStage::polygonizer() {
  return [this](const MorphRuntime& rt, double timeSec, int resolution) { return morphFrame(rt, timeSec, resolution); };
}

Result<MorphFrame> GpuImplicitStage::morphFrame(const MorphRuntime& rt, double timeSec, int resolution) {
  MorphFrame fr;
  fr.timeSec = timeSec;
  fr.stage = MorphStage::Morph;
  MorphImplicitField field = morphImplicitField(rt, timeSec, resolution);
  fr.progress = field.progress;
  fr.blend = field.blend;
  gpu::GpuField gf = gpu::GpuField::single(field.program);
  gf.colors = field.colorProgram.get();  // the vertices' colours from the GPU's colour pass, as the CPU stage's
  if (std::string why = gpu::GpuPolygonizer::unsupported(gf); !why.empty())
    return Error{"the GPU polygoniser cannot evaluate this morph: " + why};
  gpu::GpuPolygonizeSettings gs;
  gs.resolution = resolution;
  gs.bounds = field.bounds;
  gs.noiseAmplitude = field.noiseAmplitude;  // the GPU's noise pass: the CPU path's displacement
  gs.noiseFrequency = rt.setup.noiseFrequency;
  std::lock_guard<std::mutex> lock(mutex_);
  auto stats = polygonizer_->polygonize(gf, gs);
  if (!stats) return Error{stats.error()};
  auto mesh = polygonizer_->readBack();
  if (!mesh) return Error{mesh.error()};
  fr.mesh = std::move(*mesh);
  fr.polygonize.gridX = stats->gridX;
  fr.polygonize.gridY = stats->gridY;
  fr.polygonize.gridZ = stats->gridZ;
  fr.polygonize.cellSize = stats->cellSize;
  fr.polygonize.blocksTotal = stats->blocksTotal;
  fr.polygonize.blocksEvaluated = stats->blocksActive;
  fr.polygonize.blocksCulled = stats->blocksTotal - stats->blocksActive;
  fr.polygonize.milliseconds = stats->milliseconds;
  return fr;
}

}  // namespace animorph::cli
