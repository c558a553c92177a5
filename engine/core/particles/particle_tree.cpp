#include "core/particles/particle_tree.h"

#include <algorithm>
#include <cmath>
#include <mutex>

namespace animorph {

float visiblePointRadius(float radius, float intensity, float stiffness, float threshold) {
  if (!(intensity > threshold) || !(radius > 0.0f)) return 0.0f;
  float ratio = threshold / intensity;
  float t = stiffness > 0.0f ? std::pow(ratio, 1.0f / stiffness) : 0.0f;
  return radius * std::sqrt(std::max(0.0f, 1.0f - t));
}

TreeParticles treeParticles(const BlobTree& tree, double t) {
  TreeParticles out;
  float threshold = tree.threshold.evaluate(t);
  forEachParticleNode(tree.root, [&](const BlobNode& n) {
    out.nodeIds.push_back(n.id);
    out.set.position.push_back(n.vec3Param("center").evaluate(t));
    out.set.radius.push_back(visiblePointRadius(n.floatParam("radius").evaluate(t), n.floatParam("intensity").evaluate(t),
                                                n.floatParam("stiffness").evaluate(t), threshold));
  });
  return out;
}

Result<ParticleBakeReport> simulateTreeParticles(BlobTree& tree, const ParticleSettings& settings,
                                                 const ParticleBakeOptions& options) {
  if (!(options.tolerance > 0.0f) || !std::isfinite(options.tolerance))
    return Error{"particles: bake tolerance must be > 0"};
  if (!std::isfinite(options.startSec)) return Error{"particles: start time must be finite"};
  double span = double(std::lround(settings.durationSec * settings.rateHz)) / settings.rateHz;
  double sampleAt = options.reverse ? options.startSec + span : options.startSec;
  TreeParticles tp = treeParticles(tree, std::isfinite(sampleAt) ? sampleAt : options.startSec);
  if (tp.nodeIds.empty()) return Error{"particles: the tree has no point primitive to simulate"};
  auto sim = ParticleSimulation::create(tp.set, settings);
  if (!sim) return Error{sim.error()};
  ParticleBakeReport report;
  report.particles = sim->size();
  report.steps = sim->steps();
  report.impulse = sim->impulse();
  TrajectoryBakeSettings bake;
  bake.startSec = options.startSec;
  bake.rateHz = settings.rateHz;
  bake.quantum = options.quantum;
  bake.tolerance = options.tolerance;
  bake.reverse = options.reverse;
  std::vector<Vec3Track> tracks(sim->size());
  std::vector<float> errors(sim->size(), 0.0f);
  bool done = sim->forEachTrajectory([&](size_t i, const std::vector<glm::vec3>& path) {
    tracks[i] = bakeTrajectory(path, bake);
    errors[i] = trajectoryError(tracks[i], path, bake);
  });
  if (!done) {
    report.cancelled = true;
    return report;
  }
  size_t i = 0;
  forEachParticleNode(tree.root, [&](BlobNode& n) {
    report.keys += tracks[i].keys().size();
    report.maxError = std::max(report.maxError, errors[i]);
    n.vec3Param("center") = std::move(tracks[i]);
    ++i;
  });
  return report;
}

}  // namespace animorph
