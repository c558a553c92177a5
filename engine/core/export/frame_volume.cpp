#include "core/export/frame_volume.h"

namespace animorph {

FrameLevelSet morphFrameLevelSet(const MorphRuntime& rt, double timeSec, int resolution,
                                 int threads, const std::atomic<bool>* cancel, bool colors) {
  std::optional<MorphImplicitField> field = morphFrameField(rt, timeSec, resolution);
  if (!field) return std::optional<LevelSetVoxels>{};
  LevelSetSettings ls;
  ls.grid.resolution = resolution;
  ls.grid.bounds = field->bounds;  // as evaluateMorphImplicit polygonises it
  ls.grid.threads = threads;
  ls.grid.cancel = cancel;
  ls.noiseAmplitude = field->noiseAmplitude;
  ls.noiseFrequency = rt.setup.noiseFrequency;
  // Without a colour program the morph's surface has no colours (characters without their own).
  ls.colors = colors && field->colorProgram;
  ls.colorProgram = field->colorProgram.get();
  auto band = sampleLevelSet(field->program, ls);
  if (!band) return Error{band.error()};
  return std::optional<LevelSetVoxels>(std::move(*band));
}

FrameLevelSet fieldLevelSet(const FieldProgram& program, int resolution, int threads,
                            const std::atomic<bool>* cancel, bool colors) {
  LevelSetSettings ls;
  ls.grid.resolution = resolution;
  ls.grid.threads = threads;
  ls.grid.cancel = cancel;
  ls.colors = colors;
  auto band = sampleLevelSet(program, ls);
  if (!band) return Error{band.error()};
  return std::optional<LevelSetVoxels>(std::move(*band));
}

}  // namespace animorph
