#pragma once
// Projection of points onto a stand-in's surface f = 0 (docs/design.md §4, paper 1
// §3.2): Newton steps along grad f with a step limit; where the gradient
// vanishes (beyond every primitive's reach) or Newton stalls, the point jumps
// to the surface of the closest segment's capsule and Newton continues from there.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/field/field_program.h"
#include "core/standin/standin.h"

namespace animorph {

struct ProjectionSettings {
  int maxIterations = 40;      // Newton steps per point (after a fallback, the count restarts once)
  float tolerance = 1e-5f;     // |f| accepted as on the surface (f is ~T = 1 deep inside)
  float maxStepRadii = 0.5f;   // longest Newton step, in units of the median segment radius
  int threads = 0;             // 0: all hardware threads
  bool operator==(const ProjectionSettings&) const = default;
};

struct ProjectionStats {
  size_t points = 0;
  size_t converged = 0;   // |f| <= tolerance at the end
  size_t fallbacks = 0;   // points that took the closest-segment direction
  size_t failures = 0;    // not converged: left at the point of smallest |f| found
  // Per failure (in point order): |f| / |grad f| where the point was left, an estimate of its
  // distance from the surface in the points' units (INFINITY where grad f vanishes). f's float
  // noise is about the tolerance, so a point can fail within a hair of the surface: callers that
  // compare fits tell those from real misses by this distance against their scale.
  std::vector<float> failureDistances;
  float maxAbsField = 0.0f;
  double meanDistance = 0.0;  // mean |moved| (in the points' units)
  double maxDistance = 0.0;
  double milliseconds = 0.0;
};

// Moves n points onto f = 0 of prog (built from segs, which give the fallback
// direction). out[i] receives the projected point, normals[i] (if non-null) the
// outward unit normal -grad f / |grad f| there. Deterministic for any thread count.
ProjectionStats projectOntoField(const FieldProgram& prog, const std::vector<PosedSegment>& segs, const glm::vec3* in,
                                 size_t n, glm::vec3* out, glm::vec3* normals, const ProjectionSettings& settings);

// Median radius of the segments with a positive radius (0.05 when there are
// none): the unit of ProjectionSettings::maxStepRadii.
float medianSegmentRadius(const std::vector<PosedSegment>& segs);

}  // namespace animorph
