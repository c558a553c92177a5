#include "core/project/new_morph_project.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "core/standin/character_pose.h"
#include "core/standin_morph/target_alignment.h"

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

  AlignmentSettings as;
  as.alignScaleRatio = s.alignScaleRatio;
  as.alignOffsetFraction = s.alignOffsetFraction;
  as.maxRescaleWithoutConsent = s.maxRescaleWithoutConsent;
  const TargetAlignment al = alignTargetToSource(source, target, as);
  if (!al.unitNote.empty()) out.messages.push_back(al.unitNote);
  if (al.needsConsent) {
    if (!s.allowLargeRescale) return Error{targetAsset + ": " + al.sizeNote + "; allow it explicitly or export both in the same units"};
    out.warnings.push_back(targetAsset + ": " + al.sizeNote + " (allowed)");
  }
  if (al.changes()) {
    b.transform = al.transform;
    out.aligned = true;
    out.scaleApplied = al.transform.scale.x;
    const glm::vec3 t = al.transform.translation;
    out.messages.push_back(fmt("aligned the target to the source: scale factor %.4gx applied, translation (%.3g, %.3g, %.3g)",
                               out.scaleApplied, t.x, t.y, t.z));
  }
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
                     " (fit: " + fitSummary(fit->report) + ")" +
                     (fit->report.repairs.empty() ? "" : "; automatic " + repairSummary(fit->report)) +
                     "; the automatic repairs could not fix it: check the skin weights of the bones named, or fit "
                     "the stand-in by hand in the editor's Stand-in edit mode"};
      out.warnings.push_back(actor->id + ": POOR stand-in fit (accepted): " + why);
    }
    ActorMorph am;
    am.actorId = actor->id;
    am.standin = fit->standin;
    m.actors.push_back(std::move(am));
    out.messages.push_back(actor->id + ": stand-in of " + std::to_string(fit->report.segments) + " segments, fit " +
                           fitSummary(fit->report));
    if (!fit->report.repairs.empty()) out.messages.push_back(actor->id + ": " + repairSummary(fit->report));
  }
  return out;
}

}  // namespace animorph
