// animorph-cli info FILE [--json]: summary of a character (glTF, FBX, Collada, OBJ) or a project.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include <nlohmann/json.hpp>

#include "core/blobtree/tree_edit.h"
#include "app/cli/cli_command.h"
#include "core/project/project_io.h"
#include "core/io/character_import.h"
#include "core/standin/character_pose.h"

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

json vec3(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

void countNodes(const animorph::BlobNode& n, std::map<std::string, int>& byCategory) {
  ++byCategory[animorph::nodeTypeInfo(n.type).category];
  for (const auto& c : n.children) countNodes(c, byCategory);
}

json characterJson(const std::string& path, const animorph::Character& c) {
  const animorph::Bounds b = animorph::poseBounds(c);
  json j;
  j["file"] = path;
  std::string format = c.format.empty() ? "glTF" : c.format;
  std::transform(format.begin(), format.end(), format.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  j["format"] = format;
  j["unit"] = {{"name", c.unit.name}, {"metres_per_unit", c.unit.metresPerUnit}, {"declared", c.unit.declared}};
  j["materials"] = c.materials.size();
  j["vertices"] = c.totalVertices();
  j["triangles"] = c.totalTriangles();
  j["joints"] = c.totalJoints();
  j["nodes"] = c.nodes.size();
  j["meshes"] = c.meshes.size();
  j["skins"] = c.skins.size();
  j["animations"] = json::array();
  for (const auto& clip : c.clips)
    j["animations"].push_back({{"name", clip.name}, {"duration", clip.durationSec}, {"channels", clip.channels.size()}});
  if (!b.empty()) j["bounds"] = {{"min", vec3(b.min)}, {"max", vec3(b.max)}};
  const auto& r = c.report;
  j["report"] = {{"warnings", r.warnings},
                 {"unsupported", r.unsupported},
                 {"weights_normalised", r.weightsNormalised},
                 {"influences_dropped", r.influencesDropped},
                 {"normals_computed", r.normalsComputed},
                 {"import_ms", r.importMs}};
  return j;
}

void printCharacter(const std::string& path, const animorph::Character& c) {
  std::printf("%s: %s character, in %s (%.4g m per unit)\n", path.c_str(), c.format.empty() ? "glTF" : c.format.c_str(),
              c.unit.name.c_str(), c.unit.metresPerUnit);
  std::printf("  %zu meshes, %zu vertices, %zu triangles\n", c.meshes.size(), c.totalVertices(), c.totalTriangles());
  std::printf("  %zu nodes, %zu skins, %zu joints\n", c.nodes.size(), c.skins.size(), c.totalJoints());
  const animorph::Bounds b = animorph::poseBounds(c);
  if (!b.empty())
    std::printf("  bounds (%.4g, %.4g, %.4g) .. (%.4g, %.4g, %.4g), height %.4g (the file's units; rest pose with "
                "every node transform)\n",
                b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z, b.max.y - b.min.y);
  std::printf("  %zu animations\n", c.clips.size());
  for (const auto& clip : c.clips)
    std::printf("    %-24s %7.3f s  %zu channels\n", clip.name.c_str(), clip.durationSec, clip.channels.size());
  const auto& r = c.report;
  std::printf("  imported in %.1f ms; %zu vertices had weights normalised, %zu dropped influences, normals computed "
              "for %zu meshes\n",
              r.importMs, r.weightsNormalised, r.influencesDropped, r.normalsComputed);
  for (const auto& w : r.warnings) std::printf("  warning: %s\n", w.c_str());
  for (const auto& u : r.unsupported) std::printf("  not used: %s\n", u.c_str());
}

int infoProject(const std::string& path, bool asJson) {
  auto project = animorph::loadProject(path);
  if (!project) return animorph::cli::fail("info", project.error());
  const auto& p = *project;
  const fs::path dir = fs::absolute(fs::path(path)).parent_path();
  json actors = json::array();
  for (const auto& a : p.actors) {
    if (a.kind == animorph::ActorKind::BlobTree) {
      std::map<std::string, int> cats;
      countNodes(a.blobTree.root, cats);
      json ja = {{"id", a.id},
                 {"name", a.name},
                 {"kind", "blobtree"},
                 {"loads", true},
                 {"nodes", a.blobTree.root.subtreeSize()},
                 {"primitives", cats["primitive"]},
                 {"operators", cats["operator"]},
                 {"maps", cats["map"]},
                 {"meta", cats["meta"]},
                 {"animation_end", animorph::animationEndSec(a.blobTree)}};
      actors.push_back(ja);
      continue;
    }
    const std::string resolved = (dir / a.assetPath).lexically_normal().string();
    auto c = animorph::importCharacter(resolved);
    json ja = {{"id", a.id}, {"name", a.name}, {"asset", a.assetPath}, {"loads", c.ok()}, {"clip", a.clip}};
    if (!c) ja["error"] = c.error();
    else {
      ja["vertices"] = c->totalVertices();
      ja["triangles"] = c->totalTriangles();
      if (a.clip >= 0 && a.clip < static_cast<int>(c->clips.size())) ja["clip_name"] = c->clips[a.clip].name;
    }
    actors.push_back(ja);
  }
  const auto& t = p.timeline;
  if (asJson) {
    json j = {{"file", path},          {"format", "animorph"},        {"name", p.name},
              {"fps", t.fps},          {"frame_start", t.frameStart}, {"frame_end", t.frameEnd},
              {"actors", actors}};
    if (p.morph.enabled()) {
      const auto& m = p.morph;
      j["markers"] = {{"A", m.markers.a}, {"B", m.markers.b}, {"C", m.markers.c}, {"D", m.markers.d}};
      json segs = json::object();
      for (const auto& am : m.actors) segs[am.actorId] = am.standin.segments.size();
      j["morph"] = {{"source", m.sourceActorId},
                    {"target", m.targetActorId},
                    {"method", animorph::morphMethodName(m.method)},
                    {"standin_segments", segs}};
    }
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::printf("%s: Animorph project '%s'\n", path.c_str(), p.name.c_str());
  std::printf("  timeline: frames %d..%d at %g fps (%.2f s)\n", t.frameStart, t.frameEnd, t.fps,
              (t.frameEnd - t.frameStart) / t.fps);
  if (p.morph.enabled()) {
    const auto& m = p.morph;
    std::printf("  morph: %s -> %s (%s), markers A %d, B %d, C %d, D %d\n", m.sourceActorId.c_str(),
                m.targetActorId.c_str(), animorph::morphMethodName(m.method), m.markers.a, m.markers.b, m.markers.c,
                m.markers.d);
  }
  std::printf("  %zu actors\n", actors.size());
  for (const auto& a : actors) {
    if (a.contains("kind") && a["kind"] == "blobtree") {
      std::printf("    %-12s BlobTree: %d nodes (%d primitives, %d operators, %d maps, %d meta), animated over %.2f s\n",
                  a["id"].get<std::string>().c_str(), a["nodes"].get<int>(), a["primitives"].get<int>(),
                  a["operators"].get<int>(), a["maps"].get<int>(), a["meta"].get<int>(),
                  a["animation_end"].get<double>());
      continue;
    }
    std::printf("    %-12s %-40s ", a["id"].get<std::string>().c_str(), a["asset"].get<std::string>().c_str());
    if (a["loads"].get<bool>())
      std::printf("ok (%zu triangles%s%s)\n", a["triangles"].get<size_t>(), a.contains("clip_name") ? ", clip " : "",
                  a.contains("clip_name") ? a["clip_name"].get<std::string>().c_str() : "");
    else
      std::printf("DOES NOT LOAD: %s\n", a["error"].get<std::string>().c_str());
  }
  return 0;
}

int runInfo(const std::vector<std::string>& args) {
  bool asJson = false;
  std::string file;
  for (const auto& a : args) {
    if (a == "--json") asJson = true;
    else if (!a.empty() && a[0] == '-') return animorph::cli::fail("info", "unknown option " + a, 2);
    else if (file.empty()) file = a;
    else return animorph::cli::fail("info", "only one FILE is accepted", 2);
  }
  if (file.empty()) return animorph::cli::fail("info", "missing FILE (see animorph-cli info --help)", 2);
  if (fs::path(file).extension() == ".animorph") return infoProject(file, asJson);
  auto c = animorph::importCharacter(file);
  if (!c) return animorph::cli::fail("info", c.error());
  if (asJson) std::cout << characterJson(file, *c).dump(2) << "\n";
  else printCharacter(file, *c);
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("info", "summary of a character (glTF, FBX, Collada, OBJ) or an .animorph project",
                     "usage: animorph-cli info FILE [--json]\n"
                     "  FILE.gltf / .glb / .fbx / .dae / .obj: the format and length unit, meshes,\n"
                     "  vertices, triangles, skins, joints, animation clips\n"
                     "  with their durations, the bounds of the skinned rest pose in scene units (every\n"
                     "  node transform applied), and the import report (warnings, unsupported features,\n"
                     "  normalised weights).\n"
                     "  FILE.animorph: project name, frame rate, frame range, and each actor's asset\n"
                     "  with whether it loads; the morph's source, target, method and markers A..D\n"
                     "  (JSON: \"markers\": {\"A\", \"B\", \"C\", \"D\"} in frames) when it has one.\n"
                     "  --json  print the same as JSON.\n"
                     "  Exit status: 0 on success, 1 when FILE cannot be read, 2 on bad arguments.\n",
                     runInfo);
