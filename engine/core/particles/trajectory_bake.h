#pragma once
// Baking particle trajectories into ordinary key-framed tracks (docs/particles.md):
// a trajectory sampled at fixed steps becomes a Vec3Track of cubic Hermite keys at
// some of the steps, each with its derivative from central differences of the
// samples (one-sided at the ends), thinned greedily: a key is dropped wherever
// the curve through its neighbours stays within `tolerance` of every sample it
// skips. So every sample is reproduced within the tolerance (exactly at keys), a
// ballistic flight needs only its end keys, and a bounce keeps keys around it.
#include <vector>

#include <glm/glm.hpp>

#include "core/anim/track.h"

namespace animorph {

struct TrajectoryBakeSettings {
  double startSec = 0.0;   // time of sample 0
  double rateHz = 120.0;   // samples per second: sample k at startSec + k / rateHz
  float tolerance = 1e-3f; // m: largest distance between the track and a sample
  // > 0: key values are rounded to multiples of `quantum` (m) and slopes to multiples
  // of 10 quantum (m/s), so they print short; the tolerance still holds.
  double quantum = 0.0;
  bool reverse = false;    // time-reversed: sample k at the time of sample n - 1 - k
};

// The thinned track through samples (at least one).
Vec3Track bakeTrajectory(const std::vector<glm::vec3>& samples, const TrajectoryBakeSettings& settings);

// Time of sample k: (startSec * rateHz + k) / rateHz when startSec falls on a step
// (so times print short at rates such as 100 Hz), else startSec + k / rateHz.
double trajectorySampleTime(const TrajectoryBakeSettings& settings, size_t k);

// Largest distance between the track and the samples at their times.
float trajectoryError(const Vec3Track& track, const std::vector<glm::vec3>& samples,
                      const TrajectoryBakeSettings& settings);

}  // namespace animorph
