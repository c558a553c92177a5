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

struct CommonUnit {
  double metres;
  const char* name;
};
constexpr CommonUnit kCommonUnits[] = {
    {0.01, "centimetres"}, {0.001, "millimetres"}, {0.0254, "inches"}, {0.3048, "feet"}};

bool metresOrUndeclared(const LengthUnit& u) { return !u.declared || u.metresPerUnit == 1.0; }

// The first common unit (centimetres first: what Blender's glTF holds for a scene in centimetres)
// whose factor is within tolerance of a resize sizeRatio that the declared units leave: the target
// authored in it (scale by its factor) or the source (scale by the inverse), each only when that
// file declares metres or nothing. Returns the scale (1: none) and the note.
double guessUnit(const Character& source, const Character& target, double sizeRatio, double tolerance,
                 std::string& note) {
  double best = 1.0;
  std::string name;
  bool sourceSide = false;
  for (const CommonUnit& u : kCommonUnits)
    for (bool src : {false, true}) {
      if (best != 1.0 || !metresOrUndeclared(src ? source.unit : target.unit)) continue;
      const double k = src ? 1.0 / u.metres : u.metres;
      if (std::max(sizeRatio / k, k / sizeRatio) < tolerance) best = k, name = u.name, sourceSide = src;
    }
  if (best == 1.0) return 1.0;
  note = format("target is %.3gx its partner", 1.0 / sizeRatio) + " (" +
         (sourceSide ? "the partner probably authored in " : "probably authored in ") + name +
         format("): scaled by %.4g", best);
  return best;
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
  const double ds = sb.diagonal();
  double dt = std::max(1e-9, double(tb.diagonal()) * out.unitScale);
  out.sizeRatio = ds / dt;
  if (std::max(out.sizeRatio, 1.0 / out.sizeRatio) > s.maxRescaleWithoutConsent) {
    std::string note;
    out.guessedScale = guessUnit(source, target, out.sizeRatio, s.unitGuessTolerance, note);
    if (out.guessedScale != 1.0) {
      out.unitScale *= out.guessedScale;
      out.unitNote = out.unitNote.empty() ? note : out.unitNote + "; " + note;
      dt *= out.guessedScale;
      out.sizeRatio = ds / dt;
    }
  }
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
