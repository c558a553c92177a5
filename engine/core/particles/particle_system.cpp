#include "core/particles/particle_system.h"

#include <cmath>
#include <mutex>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace animorph {

namespace {

uint64_t splitmix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A unit vector from the hash of (seed, i, salt).
glm::vec3 hashedDirection(uint64_t seed, uint64_t i, uint64_t salt) {
  for (uint64_t k = 0;; ++k) {
    glm::vec3 d(hashSigned(seed, i, salt, 3 * k), hashSigned(seed, i, salt, 3 * k + 1),
                hashSigned(seed, i, salt, 3 * k + 2));
    float l = glm::length(d);
    if (l > 0.05f && l <= 1.0f) return d / l;
  }
}

// Runs fn(i) for every particle in parallel, in chunks, with progress and cancel.
template <class Fn>
bool parallelParticles(const ParticleSettings& s, size_t n, Fn&& fn) {
  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
  std::atomic<size_t> done{0};
  std::atomic<bool> stopped{false};
  std::mutex progressMutex;
  float reported = 0.0f;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& r) {
      if (stopped.load(std::memory_order_relaxed)) return;
      if (s.cancel && s.cancel->load(std::memory_order_relaxed)) {
        stopped = true;
        return;
      }
      for (size_t i = r.begin(); i != r.end(); ++i) fn(i);
      size_t d = done.fetch_add(r.size()) + r.size();
      if (s.progress) {
        std::lock_guard<std::mutex> lock(progressMutex);
        float f = float(d) / float(n);
        if (f > reported) {
          reported = f;
          s.progress(f);
        }
      }
    });
  });
  return !stopped.load();
}

}  // namespace

float hashSigned(uint64_t seed, uint64_t a, uint64_t b, uint64_t c) {
  uint64_t h = splitmix(splitmix(splitmix(seed ^ 0x5DEECE66Dull) ^ a) ^ (b * 0x100000001B3ull)) ^ c;
  h = splitmix(h);
  return float(double(h >> 40) / double(1ull << 23)) - 1.0f;
}

Result<ParticleSimulation> ParticleSimulation::create(const ParticleSet& in, const ParticleSettings& s) {
  size_t n = in.size();
  if (!(s.rateHz > 0.0 && std::isfinite(s.rateHz) && s.rateHz <= 100000.0))
    return Error{"particles: rate " + std::to_string(s.rateHz) + " Hz is not in (0, 100000]"};
  if (!(s.durationSec >= 0.0 && std::isfinite(s.durationSec) && s.durationSec * s.rateHz <= 1e6))
    return Error{"particles: duration " + std::to_string(s.durationSec) + " s is negative or too long"};
  if (!in.velocity.empty() && in.velocity.size() != n) return Error{"particles: velocity count differs from positions"};
  if (!in.mass.empty() && in.mass.size() != n) return Error{"particles: mass count differs from positions"};
  if (!in.radius.empty() && in.radius.size() != n) return Error{"particles: radius count differs from positions"};
  const ParticleForces& f = s.forces;
  if (!finite(f.gravity) || !std::isfinite(f.drag) || f.drag < 0.0f || !std::isfinite(f.noise) ||
      !(f.restitution >= 0.0f && f.restitution <= 1.0f) || !(f.friction >= 0.0f && f.friction <= 1.0f) ||
      !std::isfinite(f.groundHeight))
    return Error{"particles: forces out of range (drag >= 0, restitution and friction in [0, 1], finite values)"};
  if (f.explosion.enabled && (!finite(f.explosion.centre) || !(f.explosion.energy >= 0.0f) ||
                              !std::isfinite(f.explosion.energy) || !(f.explosion.falloff > 0.0f)))
    return Error{"particles: explosion needs a finite centre, energy >= 0 and falloff > 0"};
  if (f.vortex.enabled && (!finite(f.vortex.centre) || !finite(f.vortex.axis) || glm::length(f.vortex.axis) == 0.0f ||
                           !(f.vortex.radius > 0.0f) || !(f.vortex.coupling >= 0.0f) || !std::isfinite(f.vortex.swirl) ||
                           !std::isfinite(f.vortex.inward) || !std::isfinite(f.vortex.lift)))
    return Error{"particles: vortex needs a finite centre, a non-zero axis, radius > 0 and coupling >= 0"};

  ParticleSimulation sim;
  sim.settings_ = s;
  sim.settings_.forces.vortex.axis = f.vortex.enabled ? glm::normalize(f.vortex.axis) : f.vortex.axis;
  sim.dt_ = 1.0 / s.rateHz;
  sim.steps_ = int(std::lround(s.durationSec * s.rateHz));
  sim.pos_ = in.position;
  sim.vel_ = in.velocity.empty() ? std::vector<glm::vec3>(n, glm::vec3(0.0f)) : in.velocity;
  sim.mass_ = in.mass.empty() ? std::vector<float>(n, n ? 1.0f / float(n) : 0.0f) : in.mass;
  sim.radius_ = in.radius.empty() ? std::vector<float>(n, 0.0f) : in.radius;
  for (size_t i = 0; i < n; ++i) {
    if (!finite(sim.pos_[i]) || !finite(sim.vel_[i]))
      return Error{"particles: particle " + std::to_string(i) + " has a non-finite position or velocity"};
    if (!(sim.mass_[i] >= 0.0f) || !(sim.radius_[i] >= 0.0f) || !std::isfinite(sim.mass_[i]) ||
        !std::isfinite(sim.radius_[i]))
      return Error{"particles: particle " + std::to_string(i) + " has a negative or non-finite mass or radius"};
  }
  if (f.explosion.enabled && n > 0) {
    // Serial sums in double: the same result for any thread count.
    const ExplosionForce& e = f.explosion;
    std::vector<double> w(n);
    double mw = 0.0;
    for (size_t i = 0; i < n; ++i) {
      double d = glm::length(sim.pos_[i] - e.centre) / e.falloff;
      w[i] = 1.0 / (1.0 + d * d);
      mw += double(sim.mass_[i]) * w[i];
    }
    for (size_t i = 0; i < n && mw > 0.0; ++i) {
      glm::vec3 dir = sim.pos_[i] - e.centre;
      float l = glm::length(dir);
      dir = l > 1e-6f ? dir / l : hashedDirection(s.seed, i, 17);
      double speed = std::sqrt(2.0 * double(e.energy) * w[i] / mw);
      glm::vec3 dv = dir * float(speed);
      sim.vel_[i] += dv;
      double m = sim.mass_[i];
      sim.impulse_.momentum += m * glm::dvec3(dv);
      sim.impulse_.magnitude += m * speed;
      sim.impulse_.energy += 0.5 * m * glm::dot(glm::dvec3(dv), glm::dvec3(dv));
    }
  }
  return sim;
}

void ParticleSimulation::start(size_t i, glm::vec3& p, glm::vec3& v) const {
  p = pos_[i];
  v = vel_[i];
}

void ParticleSimulation::step(size_t i, int k, glm::vec3& p, glm::vec3& v) const {
  const ParticleForces& f = settings_.forces;
  const float dt = float(dt_);
  glm::vec3 a = f.gravity - f.drag * v;
  if (f.vortex.enabled) {
    const VortexForce& vx = f.vortex;
    glm::vec3 r = p - vx.centre;
    glm::vec3 radial = r - glm::dot(r, vx.axis) * vx.axis;
    float d = glm::length(radial);
    glm::vec3 flow = vx.lift * vx.axis;
    if (d > 1e-6f) {
      glm::vec3 out = radial / d;
      float speed = d <= vx.radius ? vx.swirl * d / vx.radius : vx.swirl * vx.radius / d;
      flow += speed * glm::cross(vx.axis, out) - vx.inward * std::min(1.0f, d / vx.radius) * out;
    }
    a += vx.coupling * (flow - v);
  }
  if (f.noise != 0.0f) {
    uint64_t ks = uint64_t(k);
    a += f.noise * glm::vec3(hashSigned(settings_.seed, i, ks, 0), hashSigned(settings_.seed, i, ks, 1),
                             hashSigned(settings_.seed, i, ks, 2));
  }
  v += a * dt;
  p += v * dt;
  if (f.ground) {
    float floor = f.groundHeight + radius_[i];
    if (p.y < floor) {
      p.y = floor;
      if (v.y < 0.0f) {
        v.y = -f.restitution * v.y;
        v.x *= 1.0f - f.friction;
        v.z *= 1.0f - f.friction;
      }
    }
  }
}

bool ParticleSimulation::run(std::vector<glm::vec3>& position, std::vector<glm::vec3>& velocity) const {
  position.resize(size());
  velocity.resize(size());
  return parallelParticles(settings_, size(), [&](size_t i) {
    glm::vec3 p, v;
    start(i, p, v);
    for (int k = 0; k < steps_; ++k) step(i, k, p, v);
    position[i] = p;
    velocity[i] = v;
  });
}

bool ParticleSimulation::forEachTrajectory(
    const std::function<void(size_t, const std::vector<glm::vec3>&)>& visit) const {
  return parallelParticles(settings_, size(), [&](size_t i) {
    thread_local std::vector<glm::vec3> path;
    path.resize(size_t(steps_) + 1);
    glm::vec3 p, v;
    start(i, p, v);
    path[0] = p;
    for (int k = 0; k < steps_; ++k) {
      step(i, k, p, v);
      path[size_t(k) + 1] = p;
    }
    visit(i, path);
  });
}

}  // namespace animorph
