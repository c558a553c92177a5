#include "core/standin_morph/target_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/standin/character_pose.h"

namespace animorph {

namespace {

std::string format(const char* f, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

}  // namespace

TargetAlignment alignTargetToSource(const Character& source, const Character& target, const AlignmentSettings& s) {
  TargetAlignment out;
  const double sm = source.unit.metresPerUnit, tm = target.unit.metresPerUnit;
  if (sm > 0.0 && tm > 0.0 && std::isfinite(tm / sm)) out.unitScale = tm / sm;
  if (out.unitScale != 1.0)
    out.unitNote = "target in " + target.unit.name + ", scaled by " + format("%.4g", out.unitScale) + " to the source's " +
                   source.unit.name;
  out.transform.scale = glm::vec3(float(out.unitScale));
  const Bounds sb = poseBounds(source), tb = poseBounds(target);
  if (sb.empty() || tb.empty()) return out;
  const double ds = sb.diagonal(), dt = std::max(1e-9, double(tb.diagonal()) * out.unitScale);
  out.sizeRatio = ds / dt;
  out.resize = out.sizeRatio > s.alignScaleRatio || out.sizeRatio < 1.0 / s.alignScaleRatio;
  const double offset = glm::length(sb.center() - tb.center() * float(out.unitScale));
  out.move = out.resize || offset > s.alignOffsetFraction * ds;
  if (out.resize && std::max(out.sizeRatio, 1.0 / out.sizeRatio) > s.maxRescaleWithoutConsent) {
    out.needsConsent = true;
    out.sizeNote = format("aligning the target to the source needs a scale of %.4gx beyond its units (the source's "
                          "diagonal is %.4g, the target's %.4g in the source's units)",
                          out.sizeRatio, ds, dt) +
                   format(": more than %gx, which no unit explains", s.maxRescaleWithoutConsent);
  }
  const double k = out.unitScale * (out.resize ? out.sizeRatio : 1.0);
  out.transform.scale = glm::vec3(float(k));
  if (out.move) {  // same centre in x and z, same floor (min y)
    const glm::vec3 tc = tb.center() * float(k), sc = sb.center();
    out.transform.translation = glm::vec3(sc.x - tc.x, sb.min.y - tb.min.y * float(k), sc.z - tc.z);
  }
  return out;
}

Transform unitsOnly(const TargetAlignment& a) {
  Transform t;
  t.scale = glm::vec3(float(a.unitScale));
  return t;
}

}  // namespace animorph
