#include "core/standin/standin_colors.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace animorph {

namespace {

// Distance from x to the capsule surface of s (negative inside), and x's place along s in [0, 1].
float capsuleDistance(const PosedSegment& s, const glm::vec3& x, float& t) {
  const glm::vec3 ab = s.b - s.a;
  const float l2 = glm::dot(ab, ab);
  t = l2 > 0.0f ? std::clamp(glm::dot(x - s.a, ab) / l2, 0.0f, 1.0f) : 0.0f;
  return glm::length(x - (s.a + t * ab)) - s.radius;
}

int sampleOf(float t) { return std::clamp(int(t * float(kSegmentColorSamples)), 0, kSegmentColorSamples - 1); }

}  // namespace

std::vector<int> closestSegments(const std::vector<PosedSegment>& segs, const glm::vec3* positions, size_t n) {
  std::vector<int> out(n, -1);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    float best = INFINITY, t = 0.0f;
    for (size_t k = 0; k < segs.size(); ++k) {
      const float d = std::abs(capsuleDistance(segs[k], positions[i], t));
      if (d < best) best = d, out[i] = int(k);
    }
  });
  return out;
}

std::vector<SegmentColors> sampleSegmentColors(const std::vector<PosedSegment>& segs, const glm::vec3* positions,
                                               const glm::vec4* colors, size_t n) {
  std::vector<SegmentColors> out(segs.size());
  if (segs.empty() || n == 0) return out;
  const std::vector<int> closest = closestSegments(segs, positions, n);
  std::vector<glm::dvec3> sum(segs.size() * kSegmentColorSamples, glm::dvec3(0.0));
  std::vector<size_t> count(sum.size(), 0);
  glm::dvec3 all(0.0);
  for (size_t i = 0; i < n; ++i) {
    all += glm::dvec3(colors[i]);
    float t = 0.0f;
    capsuleDistance(segs[size_t(closest[i])], positions[i], t);
    const size_t k = size_t(closest[i]) * kSegmentColorSamples + size_t(sampleOf(t));
    sum[k] += glm::dvec3(colors[i]);
    ++count[k];
  }
  const glm::vec3 mean(all / double(n));
  for (size_t s = 0; s < segs.size(); ++s) {
    SegmentColors& c = out[s];
    c.set = true;
    for (int k = 0; k < kSegmentColorSamples; ++k) {
      // The nearest sample with vertices (the lower one on a tie); none: every vertex's mean.
      int from = -1;
      for (int d = 0; d < kSegmentColorSamples && from < 0; ++d)
        for (int j : {k - d, k + d})
          if (from < 0 && j >= 0 && j < kSegmentColorSamples && count[s * kSegmentColorSamples + size_t(j)] > 0) from = j;
      const size_t at = s * kSegmentColorSamples + size_t(std::max(from, 0));
      c.samples[size_t(k)] = from < 0 ? mean : glm::vec3(sum[at] / double(count[at]));
    }
  }
  return out;
}

std::vector<PosedSegment> splitSegmentsForColor(const std::vector<PosedSegment>& segs) {
  std::vector<PosedSegment> out;
  out.reserve(segs.size() * kSegmentColorSamples);
  for (const PosedSegment& s : segs) {
    if (!s.colors.set || glm::length(s.b - s.a) < float(kSegmentColorSamples) * kMinSegmentLength) {
      out.push_back(s);
      continue;
    }
    for (int k = 0; k < kSegmentColorSamples; ++k) {
      PosedSegment part = s;
      part.a = s.a + (s.b - s.a) * (float(k) / kSegmentColorSamples);
      part.b = s.a + (s.b - s.a) * (float(k + 1) / kSegmentColorSamples);
      part.colors.samples.fill(s.colors.samples[size_t(k)]);
      out.push_back(part);
    }
  }
  return out;
}

}  // namespace animorph
