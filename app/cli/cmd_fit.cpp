// animorph-cli fit CHARACTER -o STANDIN.json: fits a stand-in and prints the fit error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/cli/cli_command.h"
#include "core/util/atomic_file.h"
#include "core/io/character_import.h"
#include "core/standin/fit_standin.h"
#include "core/standin/standin_json.h"

namespace {

using namespace animorph;
using json = nlohmann::json;

json segmentsJson(const FitReport& r) {
  json a = json::array();
  for (const auto& e : r.perSegment)
    a.push_back({{"bone", e.bone}, {"radius", e.radius}, {"vertices", e.vertices}, {"mean_distance", e.meanDistance},
                 {"max_distance", e.maxDistance}, {"far_share", e.farShare}});
  return a;
}

json figuresJson(const FitFigures& f) {
  return {{"segments", f.segments},           {"mean_distance", f.meanDistance},
          {"max_distance", f.maxDistance},     {"far_share", f.farShare},
          {"standin_components", f.standinComponents}, {"mesh_components", f.meshComponents},
          {"largest_gap", f.largestGap},       {"poor", f.poor}};
}

json reportJson(const FitReport& r) {
  return {{"segments", r.segments},
          {"bones_omitted", r.bonesOmitted},
          {"diagonal", r.diagonal},
          {"mean_error", r.meanError},
          {"max_error", r.maxError},
          {"projection", {{"points", r.projection.points},
                          {"converged", r.projection.converged},
                          {"fallbacks", r.projection.fallbacks},
                          {"failures", r.projection.failures},
                          {"misses", r.projectionMisses}}},
          {"milliseconds", r.milliseconds},
          {"notes", r.notes},
          {"mean_distance", r.meanDistance},
          {"max_distance", r.maxDistance},
          {"far_share", r.farShare},
          {"far_fraction", r.farFraction},
          {"standin_components", r.standinComponents},
          {"mesh_components", r.meshComponents},
          {"largest_gap", r.largestGap},
          {"bones_merged", r.bonesMerged},
          {"helper_bridges", r.helperBridges},
          {"poor", r.poor},
          {"problems", r.problems},
          {"poor_bones", r.poorBones},
          {"segments_fit", segmentsJson(r)},
          {"repairs", r.repairs},
          {"before_repair", r.repairs.empty() ? json(nullptr) : figuresJson(r.beforeRepair)}};
}

int runFit(const std::vector<std::string>& args) {
  std::string input, output;
  FitSettings fs;
  bool asJson = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= args.size()) return false;
      out = args[++i];
      return true;
    };
    std::string v;
    if (a == "-o" || a == "--output") {
      if (!value(output)) return cli::fail("fit", a + " needs a value", 2);
    } else if (a == "--kind") {
      if (!value(v)) return cli::fail("fit", "--kind needs a value", 2);
      if (v == "convolution") fs.kind = StandinKind::Convolution;
      else if (v == "capsule_union" || v == "capsules") fs.kind = StandinKind::CapsuleUnion;
      else if (v == "capsule_blend") fs.kind = StandinKind::CapsuleBlend;
      else return cli::fail("fit", "--kind: expected convolution, capsule_union or capsule_blend", 2);
    } else if (a == "--percentile") {
      if (!value(v)) return cli::fail("fit", "--percentile needs a value", 2);
      fs.radiusPercentile = std::strtof(v.c_str(), nullptr);
      if (!(fs.radiusPercentile > 0.0f && fs.radiusPercentile < 1.0f))
        return cli::fail("fit", "--percentile: expected a number in (0, 1)", 2);
    } else if (a == "--clip") {
      if (!value(v)) return cli::fail("fit", "--clip needs a value", 2);
      fs.clip = std::atoi(v.c_str());
    } else if (a == "--time") {
      if (!value(v)) return cli::fail("fit", "--time needs a value", 2);
      fs.clipTimeSec = std::strtof(v.c_str(), nullptr);
    } else if (a == "--previous") {
      fs.bridgeHelpers = false;
      fs.mergeSmallBones = false;
      fs.repair.enabled = false;
    } else if (a == "--no-repair") {
      fs.repair.enabled = false;
    } else if (a == "--json") {
      asJson = true;
    } else if (!a.empty() && a[0] == '-') {
      return cli::fail("fit", "unknown option " + a, 2);
    } else if (input.empty()) {
      input = a;
    } else {
      return cli::fail("fit", "only one CHARACTER is accepted", 2);
    }
  }
  if (input.empty() || output.empty()) return cli::fail("fit", "usage: fit CHARACTER -o STANDIN.json (see --help)", 2);
  auto c = importCharacter(input);
  if (!c) return cli::fail("fit", c.error());
  auto fit = fitStandin(*c, fs);
  if (!fit) return cli::fail("fit", fit.error());
  const FitReport& r = fit->report;
  const json report = reportJson(r);
  if (auto st = writeFileAtomic(output, standinFileText(fit->standin, input, report)); !st)
    return cli::fail("fit", st.error());
  if (asJson) {
    std::cout << json({{"file", input}, {"output", output}, {"kind", standinKindName(fit->standin.kind)},
                       {"report", report}})
                     .dump(2)
              << "\n";
    return 0;
  }
  std::printf("%s: %s stand-in of %zu segments (%zu bones dominate no vertex)\n", input.c_str(),
              standinKindName(fit->standin.kind), r.segments, r.bonesOmitted);
  std::printf("  fit error: %s\n", fitSummary(r).c_str());
  std::printf("  %zu helper-bone bridges, %zu small bones merged into their parent's segment\n", r.helperBridges,
              r.bonesMerged);
  std::printf("  per segment (scene units): bone, radius, vertices, mean, max, %% far\n");
  for (const auto& e : r.perSegment)
    std::printf("    %-24s r %-9.4g %6zu  %-9.4g %-9.4g %5.1f %%\n", e.bone.c_str(), double(e.radius), e.vertices,
                e.meanDistance, e.maxDistance, 100.0 * e.farShare);
  if (!r.repairs.empty()) std::printf("  %s\n", repairSummary(r).c_str());
  for (const auto& p : r.problems) std::printf("  POOR FIT: %s\n", p.c_str());
  std::printf("  projection: %zu vertices, %zu fallbacks, %zu failures", r.projection.points, r.projection.fallbacks,
              r.projection.failures);
  if (r.projection.failures) {  // the failure closest to the surface, in diagonals
    double nearest = INFINITY;
    for (float d : r.projection.failureDistances) nearest = std::min(nearest, double(d) / std::max(1e-12, r.diagonal));
    std::printf(" (%zu off the surface; the closest %.2g of the diagonal from it)", r.projectionMisses, nearest);
  }
  std::printf("; %.0f ms\n", r.milliseconds);
  for (const auto& n : r.notes) std::printf("  note: %s\n", n.c_str());
  std::printf("wrote %s\n", output.c_str());
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("fit", "fit a stand-in to a character (glTF, FBX, Collada, OBJ) and print the fit error",
                     "usage: animorph-cli fit CHARACTER -o STANDIN.json [--kind K] [--percentile P]\n"
                     "                        [--clip N --time T] [--no-repair] [--previous] [--json]\n"
                     "  Fits one segment per bone in world units (every node transform applied): joint ->\n"
                     "  child joint, through helper bones without vertices to the next joint with some;\n"
                     "  small bones inside their parent's body (face, finger tips) are merged into its\n"
                     "  segment; leaf joints get a short one. Each radius is the P-th percentile\n"
                     "  (default 0.65) of the distances of the vertices the segment fits.\n"
                     "  --kind convolution (default) | capsule_union | capsule_blend\n"
                     "  --clip N --time T  fit the pose at T seconds of clip N (default: rest pose)\n"
                     "  A poor first fit is repaired where it can be: a bone whose vertices lie far from\n"
                     "  its segments gets them re-placed on those vertices (side by side across a wide\n"
                     "  body), a stand-in in more pieces than the mesh gets its pieces bridged along the\n"
                     "  bone chain; a 'repaired' line gives the figures before and after.\n"
                     "  --no-repair  keep the first fit as it is\n"
                     "  --previous  the fitter without helper-bone bridging, small-bone merging and repair\n"
                     "            (for comparison): segments run to child joints even when these have no vertices\n"
                     "  Prints the fit in scene units and % of the bounding-box diagonal (mean and max\n"
                     "  vertex distance to the stand-in surface, share of vertices farther than 5 %,\n"
                     "  connected pieces of the polygonised stand-in against the mesh's), per segment,\n"
                     "  and POOR FIT lines naming the bones when it is poor; writes the stand-in as JSON.\n"
                     "  Exit status: 0 on success, 1 when the character cannot be read or fitted, 2 on\n"
                     "  bad arguments.\n",
                     runFit);
