#pragma once
// A deterministic particle system (docs/particles.md): independent particles of
// given masses under an explosion impulse, gravity, drag, a swirling vortex and
// noise, bouncing on a ground plane, integrated with a fixed step (semi-implicit
// Euler). Particles do not interact, so each one is integrated on its own, in
// parallel: results are bit-identical for a given seed whatever the thread count.
// Noise comes from a counter-based hash of (seed, particle, step).
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/util/result.h"

namespace animorph {

// An explosion at t = start: particle i gets the velocity change
//   dv_i = dir_i * sqrt(2 E w_i / sum_j m_j w_j),  w_i = 1 / (1 + (d_i / falloff)^2),
// dir_i the unit vector from the centre (a hashed direction at the centre), so the
// kinetic energy given is exactly E.
struct ExplosionForce {
  bool enabled = true;
  glm::vec3 centre{0.0f};
  float energy = 20.0f;   // J (the particles weigh 1 kg together unless masses say otherwise)
  float falloff = 1.0f;   // m: distance at which a particle gets half the weight of one at the centre
};

// A Rankine vortex around the line (centre, axis): the flow turns about the axis at
// swirl * d / radius inside the core (d <= radius) and swirl * radius / d outside,
// pulls inward at `inward` and lifts along the axis at `lift` (m/s); particles are
// dragged toward the flow at rate `coupling` (1/s).
struct VortexForce {
  bool enabled = false;
  glm::vec3 centre{0.0f};
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
  float swirl = 4.0f;     // m/s at the core radius
  float radius = 0.5f;    // m
  float inward = 0.5f;    // m/s toward the axis
  float lift = 0.8f;      // m/s along the axis
  float coupling = 2.0f;  // 1/s
};

struct ParticleForces {
  ExplosionForce explosion;
  glm::vec3 gravity{0.0f, -9.81f, 0.0f};  // m/s^2
  float drag = 0.2f;                       // 1/s: a -= drag * v
  bool ground = true;                      // collide with the plane y = groundHeight
  float groundHeight = 0.0f;
  float restitution = 0.4f;                // normal speed kept after a bounce (0..1)
  float friction = 0.2f;                   // tangential speed lost per bounce (0..1)
  VortexForce vortex;
  float noise = 0.0f;                      // m/s^2: random acceleration, new each step
};

struct ParticleSettings {
  ParticleForces forces;
  uint64_t seed = 1;
  double rateHz = 120.0;      // fixed step 1 / rateHz
  double durationSec = 3.0;   // steps = round(duration * rate)
  int threads = 0;            // 0: all hardware threads
  std::function<void(float)> progress;       // fraction done, one call at a time
  const std::atomic<bool>* cancel = nullptr;  // stops early: the result is cancelled
};

// Initial state: positions, velocities (empty: at rest), masses (empty: 1 kg in all,
// shared equally) and radii (particles touch the ground at y = ground + radius; empty: 0).
struct ParticleSet {
  std::vector<glm::vec3> position;
  std::vector<glm::vec3> velocity;
  std::vector<float> mass;
  std::vector<float> radius;
  size_t size() const { return position.size(); }
};

// What the explosion gave: total momentum (vector), sum of |m dv| and the kinetic energy.
struct ImpulseReport {
  glm::dvec3 momentum{0.0};
  double magnitude = 0.0;
  double energy = 0.0;
};

// A fixed-step integrator for the particles of one set; step k is at time k / rateHz.
class ParticleSimulation {
 public:
  // Errors: non-finite input, bad rate or duration, mismatched array sizes, negative masses or radii.
  static Result<ParticleSimulation> create(const ParticleSet& initial, const ParticleSettings& settings);

  size_t size() const { return pos_.size(); }
  int steps() const { return steps_; }
  double dt() const { return dt_; }
  const ImpulseReport& impulse() const { return impulse_; }
  float mass(size_t i) const { return mass_[i]; }

  // Position and velocity of particle i at step 0 (explosion applied).
  void start(size_t i, glm::vec3& p, glm::vec3& v) const;
  // Advances particle i from step k to k + 1.
  void step(size_t i, int k, glm::vec3& p, glm::vec3& v) const;

  // Runs every particle to the end (in parallel); positions and velocities after the last step.
  // Returns false when cancelled.
  bool run(std::vector<glm::vec3>& position, std::vector<glm::vec3>& velocity) const;
  // Calls visit(i, trajectory of steps() + 1 positions) for every particle, in parallel
  // (visit must be safe to call concurrently for different i). Returns false when cancelled.
  bool forEachTrajectory(const std::function<void(size_t, const std::vector<glm::vec3>&)>& visit) const;

  const ParticleSettings& settings() const { return settings_; }

 private:
  ParticleSettings settings_;
  std::vector<glm::vec3> pos_, vel_;  // after the explosion
  std::vector<float> mass_, radius_;
  double dt_ = 0.0;
  int steps_ = 0;
  ImpulseReport impulse_;
};

// Deterministic pseudo-random numbers from a counter: a float in [-1, 1).
float hashSigned(uint64_t seed, uint64_t a, uint64_t b, uint64_t c);

}  // namespace animorph
