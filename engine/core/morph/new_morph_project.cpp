#include "morph/new_morph_project.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "standin/character_pose.h"

namespace animorph {

namespace {

std::string idFromPath(const std::string& path, const std::string& fallback) {
  std::string stem = std::filesystem::path(path).stem().string();
  std::string id;
  for (char ch : stem) id += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-') ? ch : '_';
  return id.empty() ? fallback : id;
}

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

// The target's numbers in the source's units: the ratio of their declared units.
double unitScale(const Character& source, const Character& target) {
  const double s = source.unit.metresPerUnit, t = target.unit.metresPerUnit;
  return s > 0.0 && t > 0.0 && std::isfinite(s / t) ? t / s : 1.0;
}

// Scales and moves the target onto the source: first by their units, then, when the sizes
// still differ a lot or the centres are far apart, onto the source's bounding box. Only the
// part of the scale that the units do not explain needs consent.
Status alignTarget(const Character& source, const Character& target, const std::string& targetAsset,
                   const NewMorphSettings& s, Actor& b, NewMorphProject& out) {
  const double units = unitScale(source, target);
  if (units != 1.0)
    out.messages.push_back("target in " + target.unit.name + ", scaled by " + fmt("%.4g", units) + " to the source's " +
                           source.unit.name);
  const Bounds sb = poseBounds(source), tb = poseBounds(target);
  double k = units;
  glm::vec3 move(0.0f);
  bool aligned = units != 1.0;
  if (!sb.empty() && !tb.empty()) {
    const double ds = sb.diagonal(), dt = std::max(1e-9, double(tb.diagonal()) * units);
    const double ratio = ds / dt;  // what the units leave unexplained
    const glm::vec3 tcUnits = tb.center() * float(units);
    const double offset = glm::length(sb.center() - tcUnits);
    const bool resize = ratio > s.alignScaleRatio || ratio < 1.0 / s.alignScaleRatio;
    if (resize || offset > s.alignOffsetFraction * ds) {
      if (resize && std::max(ratio, 1.0 / ratio) > s.maxRescaleWithoutConsent) {
        const std::string what = fmt("aligning the target to the source needs a scale of %.4gx beyond its units (the "
                                     "source's diagonal is %.4g, the target's %.4g in the source's units)",
                                     ratio, ds, dt);
        if (!s.allowLargeRescale)
          return Error{targetAsset + ": " + what + fmt(": more than %gx, which no unit explains; allow it explicitly "
                                                       "or export both in the same units",
                                                       s.maxRescaleWithoutConsent)};
        out.warnings.push_back(targetAsset + ": " + what + " (allowed)");
      }
      if (resize) k = units * ratio;
      // Same centre in x and z, same floor (min y).
      const glm::vec3 tc = tb.center() * float(k), sc = sb.center();
      move = glm::vec3(sc.x - tc.x, sb.min.y - tb.min.y * float(k), sc.z - tc.z);
      aligned = true;
    }
  }
  if (!aligned) return {};
  out.aligned = true;
  out.scaleApplied = k;
  b.transform.scale = glm::vec3(float(k));
  b.transform.translation = move;
  out.messages.push_back(fmt("aligned the target to the source: scale factor %.4gx applied, translation (%.3g, %.3g, %.3g)",
                             k, move.x, move.y, move.z));
  return {};
}

}  // namespace

Result<NewMorphProject> makeMorphProject(const Character& source, const std::string& sourceAsset,
                                         const Character& target, const std::string& targetAsset,
                                         const NewMorphSettings& s) {
  NewMorphProject out;
  Project& p = out.project;
  p.name = idFromPath(sourceAsset, "source") + "_to_" + idFromPath(targetAsset, "target");
  Actor a, b;
  a.id = idFromPath(sourceAsset, "source");
  b.id = idFromPath(targetAsset, "target");
  if (b.id == a.id) b.id = a.id + "_2";
  a.name = a.id;
  b.name = b.id;
  a.assetPath = sourceAsset;
  b.assetPath = targetAsset;

  if (auto st = alignTarget(source, target, targetAsset, s, b, out); !st) return Error{st.error()};
  p.actors = {a, b};
  p.timeline.fps = s.fps;
  p.timeline.frameStart = 0;
  p.timeline.frameEnd = int(std::lround(s.endSec * s.fps));
  p.timeline.currentFrame = 0;

  MorphSetup& m = p.morph;
  m.sourceActorId = a.id;
  m.targetActorId = b.id;
  m.markers = {int(std::lround(s.aSec * s.fps)), int(std::lround(s.bSec * s.fps)), int(std::lround(s.cSec * s.fps)),
               int(std::lround(s.dSec * s.fps))};
  m.method = s.method;
  for (const auto& [actor, character, report] :
       {std::tuple{&a, &source, &out.sourceFit}, std::tuple{&b, &target, &out.targetFit}}) {
    auto fit = fitStandin(*character, s.fit);
    if (!fit) return Error{actor->assetPath + ": " + fit.error()};
    *report = fit->report;
    if (fit->report.poor) {
      std::string why;
      for (const auto& p : fit->report.problems) why += (why.empty() ? "" : "; ") + p;
      if (!s.acceptPoorFit)
        return Error{actor->assetPath + ": the automatic stand-in fits poorly: " + why +
                     " (fit: " + fitSummary(fit->report) + ")"};
      out.warnings.push_back(actor->id + ": POOR stand-in fit (accepted): " + why);
    }
    ActorMorph am;
    am.actorId = actor->id;
    am.standin = fit->standin;
    m.actors.push_back(std::move(am));
    out.messages.push_back(actor->id + ": stand-in of " + std::to_string(fit->report.segments) + " segments, fit " +
                           fitSummary(fit->report));
  }
  return out;
}

}  // namespace animorph
