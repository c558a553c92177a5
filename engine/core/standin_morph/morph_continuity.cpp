#include "core/standin_morph/morph_continuity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/standin_morph/mesh_distance.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/union_volume.h"

namespace animorph {

double relativeVolumeChange(double a, double b) {
  const double m = std::max(std::abs(a), std::abs(b));
  return m > 0.0 ? std::abs(b - a) / m : 0.0;
}

double hausdorffDistance(const TriangleMesh& a, const TriangleMesh& b) {
  const bool ea = a.triangleCount() == 0, eb = b.triangleCount() == 0;
  if (ea && eb) return 0.0;
  if (ea || eb) return std::numeric_limits<double>::infinity();
  return std::max(maxPointToMeshDistance(a.positions, b), maxPointToMeshDistance(b.positions, a));
}

FrameMeasure measureFrame(int frame, const TriangleMesh& mesh, const TriangleMesh* previous, size_t coreTriangles) {
  FrameMeasure m;
  m.frame = frame;
  m.triangles = mesh.triangleCount();
  if (coreTriangles > 0 && coreTriangles <= m.triangles)
    m.volume = unionVolume(mesh, {0, m.triangles - coreTriangles});
  else
    m.volume = m.triangles > 0 ? meshVolume(mesh) : 0.0;
  if (previous) m.hausdorff = hausdorffDistance(*previous, mesh);
  return m;
}

std::vector<ContinuityDefect> continuityDefects(const std::vector<FrameMeasure>& frames, double maxChange) {
  std::vector<ContinuityDefect> out;
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameMeasure& f = frames[i];
    if (f.triangles == 0) {
      out.push_back({f.frame, "empty"});
      continue;
    }
    if (i == 0 || frames[i - 1].triangles == 0) continue;
    const FrameMeasure& p = frames[i - 1];
    if (relativeVolumeChange(p.volume, f.volume) > maxChange) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "volume %+.0f%% from frame %d", 100.0 * (f.volume - p.volume) / std::abs(p.volume),
                    p.frame);
      out.push_back({f.frame, buf});
    }
  }
  return out;
}

ContinuitySummary measureContinuity(int first, int last, const std::function<FrameShape(int)>& shapeOf,
                                    bool hausdorff) {
  ContinuitySummary s;
  TriangleMesh prev;
  for (int f = first; f <= last; ++f) {
    FrameShape shape = shapeOf(f);
    TriangleMesh& mesh = shape.mesh;
    s.frames.push_back(measureFrame(f, mesh, hausdorff && f > first ? &prev : nullptr, shape.coreTriangles));
    const FrameMeasure& m = s.frames.back();
    s.emptyFrames += m.triangles == 0;
    if (f > first) {
      const double dv = relativeVolumeChange(s.frames[s.frames.size() - 2].volume, m.volume);
      if (dv > s.maxVolumeChange) s.maxVolumeChange = dv, s.maxVolumeFrame = f;
      if (m.hausdorff > s.maxHausdorff) s.maxHausdorff = m.hausdorff, s.maxHausdorffFrame = f;
    }
    prev = std::move(mesh);
  }
  return s;
}

}  // namespace animorph
