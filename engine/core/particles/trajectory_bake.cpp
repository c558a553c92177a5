#include "core/particles/trajectory_bake.h"

#include <algorithm>
#include <cmath>

namespace animorph {

namespace {

// Sample k of the (possibly reversed) trajectory, in timeline order.
struct Ordered {
  const std::vector<glm::vec3>& s;
  bool reverse;
  size_t n() const { return s.size(); }
  const glm::vec3& operator[](size_t k) const { return reverse ? s[s.size() - 1 - k] : s[k]; }
};

// Derivative (per second) at sample k: central difference, one-sided at the ends.
glm::vec3 slope(const Ordered& o, size_t k, float h) {
  size_t n = o.n();
  if (n < 2) return glm::vec3(0.0f);
  if (k == 0) return (o[1] - o[0]) / h;
  if (k + 1 == n) return (o[k] - o[k - 1]) / h;
  return (o[k + 1] - o[k - 1]) / (2.0f * h);
}

// True when the cubic Hermite segment from key a to key b (as Track evaluates it)
// stays within tol of every sample in between.
bool segmentFits(const Ordered& o, const std::vector<glm::vec3>& value, size_t a, size_t b,
                 const std::vector<glm::vec3>& d, float step, float tol) {
  float h = float(b - a) * step;
  glm::vec3 dp = value[b] - value[a];
  glm::vec3 c1 = d[a] * h;
  glm::vec3 c2 = dp * 3.0f - d[a] * (2.0f * h) - d[b] * h;
  glm::vec3 c3 = dp * -2.0f + d[a] * h + d[b] * h;
  float tol2 = tol * tol;
  for (size_t k = a + 1; k < b; ++k) {
    float s = float(k - a) / float(b - a);
    glm::vec3 p = value[a] + s * (c1 + s * (c2 + s * c3));
    glm::vec3 e = p - o[k];
    if (glm::dot(e, e) > tol2) return false;
  }
  return true;
}

// The float nearest to a multiple of q (in double, so 0.0584 stays 0.0584 and prints short).
float roundTo(float v, double q) { return q > 0.0 ? float(std::round(double(v) / q) * q) : v; }
glm::vec3 roundTo(const glm::vec3& v, double q) { return glm::vec3(roundTo(v.x, q), roundTo(v.y, q), roundTo(v.z, q)); }

}  // namespace

double trajectorySampleTime(const TrajectoryBakeSettings& st, size_t k) {
  double first = st.startSec * st.rateHz;
  if (std::abs(first - std::round(first)) < 1e-9) return (std::round(first) + double(k)) / st.rateHz;
  return st.startSec + double(k) / st.rateHz;
}

Vec3Track bakeTrajectory(const std::vector<glm::vec3>& samples, const TrajectoryBakeSettings& st) {
  Ordered o{samples, st.reverse};
  size_t n = o.n();
  Vec3Track track;
  track.clearKeys();
  if (n == 0) return Vec3Track(glm::vec3(0.0f));
  float h = float(1.0 / st.rateHz);
  // Key candidates: rounded values and slopes; segments are checked with them.
  std::vector<glm::vec3> value(n), d(n);
  for (size_t k = 0; k < n; ++k) {
    value[k] = roundTo(o[k], st.quantum);
    d[k] = roundTo(slope(o, k, h), 10.0 * st.quantum);
  }
  // The check works in floats: keep a margin for the track's own rounding and for
  // the rounded key values (each within sqrt(3) quantum / 2 of its sample).
  float tol = st.tolerance * 0.98f - 0.87f * float(st.quantum);
  auto addKey = [&](size_t k) {
    TrackKey<glm::vec3> key;
    key.timeSec = trajectorySampleTime(st, k);
    key.value = value[k];
    key.interp = KeyInterp::Hermite;
    key.userDerivatives = true;
    key.d1 = d[k];
    track.keys().push_back(key);
  };
  bool still = true;
  for (size_t k = 1; k < n && still; ++k) still = o[k] == o[0];
  addKey(0);
  if (still) {
    track.keys()[0].userDerivatives = false;
    track.keys()[0].d1 = glm::vec3(0.0f);
    return track;
  }
  size_t a = 0;
  while (a + 1 < n) {
    // Exponential then binary search for the farthest key b the segment from a reaches.
    size_t good = a + 1, len = 2;
    size_t bad = n;
    while (a + len < n) {
      if (segmentFits(o, value, a, a + len, d, h, tol)) {
        good = a + len;
        len *= 2;
      } else {
        bad = a + len;
        break;
      }
    }
    if (bad == n && good != n - 1 && segmentFits(o, value, a, n - 1, d, h, tol)) good = n - 1;
    else {
      size_t lo = good, hi = std::min(bad, n);
      while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (segmentFits(o, value, a, mid, d, h, tol)) lo = mid;
        else hi = mid;
      }
      good = lo;
    }
    addKey(good);
    a = good;
  }
  return track;
}

float trajectoryError(const Vec3Track& track, const std::vector<glm::vec3>& samples, const TrajectoryBakeSettings& st) {
  Ordered o{samples, st.reverse};
  float worst = 0.0f;
  for (size_t k = 0; k < o.n(); ++k)
    worst = std::max(worst, glm::length(track.evaluate(trajectorySampleTime(st, k)) - o[k]));
  return worst;
}

}  // namespace animorph
