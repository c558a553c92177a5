#include "core/scene/standin_core.h"

#include <algorithm>

#include "core/poly/solid_noise.h"

namespace animorph {

namespace {

float coreBound(const MorphSetup& m) {
  return m.interpolationBound > 1.0f ? m.interpolationBound : kDefaultInterpolationBound;
}

}  // namespace

float standinCoreScale(const MorphSetup& setup, bool expand, double u) {
  // The core lasts the part of the transition next to the implicit stage: its own progress v.
  const double v = expand ? u / kStandinCoreSpan : 1.0 - (1.0 - u) / kStandinCoreSpan;
  const float uc = float(std::clamp(v, 0.0, 1.0));
  float e = std::clamp(setup.easing.evaluate(uc), 0.0f, 1.0f);
  if (uc <= 0.0f) e = 0.0f;
  if (uc >= 1.0f) e = 1.0f;
  const float inv = 1.0f / coreBound(setup);
  return inv + (1.0f - inv) * (expand ? 1.0f - e : e);
}

std::optional<MorphImplicitField> standinCoreField(const MorphRuntime& rt, double timeSec, bool expand, double u) {
  const MorphActorRuntime& a = expand ? rt.target : rt.source;
  if (a.isTree()) return std::nullopt;
  const MorphSetup& m = rt.setup;
  const float K = coreBound(m);
  const float c = standinCoreScale(m, expand, u);
  if (c * K <= 1.0f + 1e-4f) return std::nullopt;  // capped at c K T: below the threshold everywhere
  MorphImplicitField out;
  out.progress = std::clamp(u, 0.0, 1.0);
  out.blend = expand ? 1.0f : 0.0f;
  // The stand-in as the morph ends (expansion) or starts (collapse): segment tracks at u = 1 / 0.
  MorphOperand op = posedOperand(a, timeSec, expand ? 1.0 : 0.0);
  // Segments shorten about their middles as the core melts (1 at c = 1, 0 at c = 1/K).
  const float shrink = (c - 1.0f / K) / (1.0f - 1.0f / K);
  for (PosedSegment& g : op.segments) {
    const glm::vec3 mid = 0.5f * (g.a + g.b);
    g.a = mid + shrink * (g.a - mid);
    g.b = mid + shrink * (g.b - mid);
  }
  auto build = [&](FieldProgram& p, bool colorProfiles) {
    p.threshold = kStandinThreshold;
    appendMorphOperand(p, op, 1.0f, colorProfiles);
    if (c < 1.0f) {
      const float prm[2] = {c, K};
      p.addOperator(OpCode::Remap, 1, prm, 2);
    }
    p.finish();
  };
  build(out.program, false);
  if (a.binding.hasColors()) {
    auto colors = std::make_shared<FieldProgram>();
    build(*colors, true);
    out.colorProgram = std::move(colors);
  }
  out.noiseAmplitude = m.noiseAmplitude.evaluate(expand ? 1.0 : 0.0);
  return out;
}

Status appendStandinCore(const MorphRuntime& rt, MorphFrame& fr, const MorphFrameSettings& settings) {
  const bool expand = fr.stage == MorphStage::Expand;
  if (!expand && fr.stage != MorphStage::Collapse) return Status::success();
  const std::optional<MorphImplicitField> field = standinCoreField(rt, fr.timeSec, expand, fr.progress);
  if (!field) return Status::success();
  PolygonizeSettings ps;
  ps.resolution = settings.resolution;
  ps.threads = settings.threads;
  ps.cancel = settings.cancel;
  ps.bounds = field->bounds;
  ps.colors = settings.colors && field->colorProgram;
  ps.colorProgram = field->colorProgram.get();
  auto r = polygonize(field->program, ps);
  if (!r) return Error{"stand-in core at " + std::to_string(fr.timeSec) + " s: " + r.error()};
  fr.cancelled = fr.cancelled || r->cancelled;
  fr.polygonize = r->stats;
  TriangleMesh& core = r->mesh;
  displaceBySolidNoise(core, field->noiseAmplitude, rt.setup.noiseFrequency);
  if (core.indices.empty()) return Status::success();
  TriangleMesh& mesh = fr.mesh;
  const uint32_t first = uint32_t(mesh.positions.size());
  // Colours when the mesh has them for every vertex (or has no vertex: the preview's core alone).
  const bool colors = mesh.colors.size() == mesh.positions.size() && (first == 0 || !mesh.colors.empty());
  mesh.positions.insert(mesh.positions.end(), core.positions.begin(), core.positions.end());
  if (mesh.normals.size() == first && core.normals.size() == core.positions.size())
    mesh.normals.insert(mesh.normals.end(), core.normals.begin(), core.normals.end());
  // The mesh's vertex colours, when it has them: the core's own (the stand-in's colours), else
  // the mesh's mean.
  if (colors && core.colors.size() == core.positions.size()) {
    mesh.colors.insert(mesh.colors.end(), core.colors.begin(), core.colors.end());
  } else if (colors && first > 0) {
    glm::vec4 mean(0.0f);
    for (size_t i = 0; i < first; ++i) mean += mesh.colors[i];
    mesh.colors.resize(mesh.positions.size(), first ? mean / float(first) : glm::vec4(1.0f));
  }
  for (uint32_t i : core.indices) mesh.indices.push_back(first + i);
  fr.coreTriangles = core.triangleCount();
  return Status::success();
}

}  // namespace animorph
