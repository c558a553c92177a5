#include "core/standin/project_onto_standin.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace animorph {

namespace {

constexpr size_t kChunk = 256;

struct Scratch {
  FieldEvaluator evaluator;
  ActiveProgram active;
  bool ready = false;
  std::vector<float> x, y, z, f, gx, gy, gz;
  std::vector<uint32_t> live;
};

}  // namespace

float medianSegmentRadius(const std::vector<PosedSegment>& segs) {
  std::vector<float> r;
  for (const auto& s : segs)
    if (s.radius > 0.0f) r.push_back(s.radius);
  if (r.empty()) return 0.05f;
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
  return r[r.size() / 2];
}

ProjectionStats projectOntoField(const FieldProgram& prog, const std::vector<PosedSegment>& segs, const glm::vec3* in,
                                 size_t n, glm::vec3* out, glm::vec3* normals, const ProjectionSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  ProjectionStats st;
  st.points = n;
  const float maxStep = std::max(1e-6f, s.maxStepRadii * medianSegmentRadius(segs));
  const float tol = s.tolerance;
  const float T = prog.threshold;
  const size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<uint8_t> fellBack(n, 0), failed(n, 0);
  std::vector<float> finalF(n, 0.0f), finalG(n, 0.0f);
  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), chunks, [&](size_t ci) {
      Scratch& sc = scratch.local();
      if (!sc.ready) {
        prog.specialiseAll(sc.active);
        sc.ready = true;
      }
      const size_t b = ci * kChunk, e = std::min(n, b + kChunk);
      const size_t m = e - b;
      sc.x.resize(m); sc.y.resize(m); sc.z.resize(m); sc.f.resize(m);
      sc.gx.resize(m); sc.gy.resize(m); sc.gz.resize(m);
      std::vector<glm::vec3> pos(in + b, in + e), best(pos);
      std::vector<float> bestF(m, INFINITY);
      std::vector<glm::vec3> grad(m, glm::vec3(0.0f));
      std::vector<int> iter(m, 0);
      std::vector<uint8_t> done(m, 0);
      sc.live.clear();
      for (uint32_t k = 0; k < m; ++k) sc.live.push_back(k);
      const int rounds = 2 * s.maxIterations + 2;
      for (int round = 0; round < rounds && !sc.live.empty(); ++round) {
        const size_t L = sc.live.size();
        for (size_t q = 0; q < L; ++q) {
          const glm::vec3& p = pos[sc.live[q]];
          sc.x[q] = p.x; sc.y[q] = p.y; sc.z[q] = p.z;
        }
        sc.evaluator.evaluate(prog, sc.active, sc.x.data(), sc.y.data(), sc.z.data(), int(L), sc.f.data(), sc.gx.data(),
                              sc.gy.data(), sc.gz.data());
        size_t keep = 0;
        for (size_t q = 0; q < L; ++q) {
          const uint32_t k = sc.live[q];
          const float f = sc.f[q];
          const glm::vec3 g(sc.gx[q], sc.gy[q], sc.gz[q]);
          if (std::abs(f) < std::abs(bestF[k])) {
            bestF[k] = f;
            best[k] = pos[k];
            grad[k] = g;
          }
          if (std::abs(f) <= tol) { done[k] = 1; continue; }
          const float g2 = glm::dot(g, g);
          const bool flat = !(g2 > 1e-12f * T * T) || f <= -T * (1.0f - 1e-6f);
          const bool stalled = iter[k] >= s.maxIterations;
          if (flat || stalled) {
            if (fellBack[b + k] || segs.empty()) { done[k] = 1; failed[b + k] = 1; continue; }
            glm::vec3 sp;
            closestSegmentSurface(segs, pos[k], sp);
            pos[k] = sp;
            fellBack[b + k] = 1;
            iter[k] = 0;
            sc.live[keep++] = k;
            continue;
          }
          glm::vec3 step = -f * g / g2;
          const float len = glm::length(step);
          if (len > maxStep) step *= maxStep / len;
          pos[k] += step;
          ++iter[k];
          sc.live[keep++] = k;
        }
        sc.live.resize(keep);
      }
      for (uint32_t k : sc.live) failed[b + k] = 1;
      for (size_t k = 0; k < m; ++k) {
        out[b + k] = best[k];
        finalF[b + k] = bestF[k];
        finalG[b + k] = glm::length(grad[k]);
        if (std::abs(bestF[k]) > tol) failed[b + k] = 1;
        if (normals) {
          const float gl = glm::length(grad[k]);
          normals[b + k] = gl > 0.0f ? -grad[k] / gl : glm::vec3(0, 1, 0);
        }
      }
    });
  });
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    st.fallbacks += fellBack[i];
    st.failures += failed[i];
    if (failed[i])
      st.failureDistances.push_back(finalG[i] > 0.0f ? std::abs(finalF[i]) / finalG[i] : INFINITY);
    st.maxAbsField = std::max(st.maxAbsField, std::abs(finalF[i]));
    const double d = glm::length(out[i] - in[i]);
    sum += d;
    st.maxDistance = std::max(st.maxDistance, d);
  }
  st.converged = n - st.failures;
  st.meanDistance = n ? sum / double(n) : 0.0;
  st.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return st;
}

}  // namespace animorph
