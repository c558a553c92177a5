#include "core/project/project_io.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <nlohmann/json.hpp>

#include "core/blobtree/blob_tree_json.h"
#include "core/project/animorphosis_project.h"
#include "core/project/animorphosis_setup_json.h"
#include "core/util/atomic_file.h"
#include "core/project/export_settings_json.h"
#include "core/project/morph_setup_json.h"
#include "core/util/json_fields.h"
#include "core/util/json_text.h"

namespace animorph {
namespace {

using json = nlohmann::json;

json vec3Json(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

using Reader = JsonFieldReader;

}  // namespace

std::string projectToJson(const Project& p) {
  json j;
  j["format"] = "animorph";
  j["version"] = kProjectFormatVersion;
  j["name"] = p.name;
  const Timeline& t = p.timeline;
  j["timeline"] = {{"fps", t.fps},         {"frame_start", t.frameStart},       {"frame_end", t.frameEnd},
                   {"current_frame", t.currentFrame}, {"playback_speed", t.playbackSpeed}, {"loop", t.loop}};
  j["view"] = {{"grid", p.view.showGrid}, {"skeleton", p.view.showSkeleton},
               {"wireframe", p.view.wireframe}, {"axes", p.view.showAxes},
               {"standins", p.view.showStandins}};
  if (!(p.exportSettings == ExportSettings{})) j["export"] = exportSettingsToJson(p.exportSettings);
  if (!(p.playblastSettings == PlayblastSettings{})) j["playblast"] = playblastSettingsToJson(p.playblastSettings);
  json actors = json::array();
  for (const Actor& a : p.actors) {
    const glm::quat& q = a.transform.rotation;
    json ja = {{"id", a.id},
               {"name", a.name},
               {"asset", a.assetPath},
               {"clip", a.clip},
               {"time_offset", a.timeOffsetSec},
               {"speed", a.speed},
               {"loop", a.loop},
               {"visible", a.visible},
               {"translation", vec3Json(a.transform.translation)},
               {"rotation", json::array({q.x, q.y, q.z, q.w})},
               {"scale", vec3Json(a.transform.scale)}};
    // glTF actors are written exactly as before "kind" existed (a missing kind means glTF).
    if (a.kind == ActorKind::BlobTree) {
      ja["kind"] = "blobtree";
      ja.erase("asset");
      ja.erase("clip");
      ja["blobtree"] = blobTreeToJson(a.blobTree);
    }
    actors.push_back(std::move(ja));
  }
  j["actors"] = actors;
  // The morph is written only while both of its actors exist (an actor deleted
  // in the editor must not make the saved file unreadable); entries of other
  // removed actors are dropped.
  if (p.morph.enabled() && p.findActor(p.morph.sourceActorId) && p.findActor(p.morph.targetActorId) &&
      p.morph.sourceActorId != p.morph.targetActorId) {
    MorphSetup m = p.morph;
    std::erase_if(m.actors, [&](const ActorMorph& a) { return !p.findActor(a.actorId); });
    j["morph"] = morphSetupToJson(m);
  }
  // Likewise the animorphosis, while both of its BlobTree actors exist, with the links an edit of
  // their trees left valid.
  if (p.animorphosis.enabled()) {
    const Actor* source = p.findActor(p.animorphosis.sourceActorId);
    const Actor* target = p.findActor(p.animorphosis.targetActorId);
    if (source && target && source != target && source->kind == ActorKind::BlobTree &&
        target->kind == ActorKind::BlobTree) {
      AnimorphosisSetup a = p.animorphosis;
      a.graph = stillValidLinks(p);
      j["animorphosis"] = animorphosisSetupToJson(a);
    }
  }
  return j.dump(2) + "\n";
}

namespace {

// "format" and "version": an Animorph project this build can read.
Status checkProjectVersion(const json& j, const std::string& sourceName) {
  if (!j.contains("format") || j["format"] != "animorph")
    return Error{sourceName + ": not an Animorph project (missing \"format\": \"animorph\")"};
  if (!j.contains("version")) return Error{sourceName + ": version: missing"};
  std::string why;
  auto readVersion = jsonInteger(j["version"], std::numeric_limits<long long>::min(),
                                 std::numeric_limits<long long>::max(), why);
  if (!readVersion) return Error{sourceName + ": version: " + why};
  const long long version = *readVersion;
  if (version > kProjectFormatVersion)
    return Error{sourceName + ": version " + std::to_string(version) +
                 " is newer than this Animorph understands (" + std::to_string(kProjectFormatVersion) +
                 "); update Animorph to open it"};
  if (version < 1) return Error{sourceName + ": version " + std::to_string(version) + " is not valid"};
  return Status::success();
}

// The timeline's fields into tl; a bad value is failed on r (the first one wins).
void readTimeline(const json& t, Reader& r, Timeline& tl) {
  tl.fps = r.number(t, "fps", "timeline", tl.fps);
  tl.frameStart = r.integer(t, "frame_start", "timeline", tl.frameStart, -kMaxFrame, kMaxFrame);
  tl.frameEnd = r.integer(t, "frame_end", "timeline", tl.frameEnd, -kMaxFrame, kMaxFrame);
  tl.currentFrame = r.integer(t, "current_frame", "timeline", tl.currentFrame, -kMaxFrame, kMaxFrame);
  tl.playbackSpeed = r.number(t, "playback_speed", "timeline", tl.playbackSpeed);
  tl.loop = r.boolean(t, "loop", "timeline", tl.loop);
  if (!r.failed() && !(tl.fps >= kMinFps && tl.fps <= kMaxFps)) {
    std::ostringstream range;
    range << "must be in [" << kMinFps << ", " << kMaxFps << "] frames per second";
    r.fail("timeline.fps", range.str());
  }
  if (!r.failed() && tl.frameEnd < tl.frameStart) r.fail("timeline.frame_end", "is before frame_start");
  if (!r.failed() && !(tl.playbackSpeed > 0.0)) r.fail("timeline.playback_speed", "must be positive");
}

void readView(const json& v, Reader& r, ViewOptions& view) {
  view.showGrid = r.boolean(v, "grid", "view", view.showGrid);
  view.showSkeleton = r.boolean(v, "skeleton", "view", view.showSkeleton);
  view.wireframe = r.boolean(v, "wireframe", "view", view.wireframe);
  view.showAxes = r.boolean(v, "axes", "view", view.showAxes);
  view.showStandins = r.boolean(v, "standins", "view", view.showStandins);
}

// actors[i] (where) appended to p.actors; a bad field is failed on r and the actor left out. An
// error only for a BlobTree that cannot be read (its message names the actor and the node).
Status readActor(const json& a, const std::string& where, Reader& r, Project& p, const std::string& sourceName) {
  Actor act;
  act.id = r.string(a, "id", where, "", true);
  act.name = r.string(a, "name", where, act.id);
  std::string kind = r.string(a, "kind", where, "gltf");
  if (kind == "blobtree") act.kind = ActorKind::BlobTree;
  else if (kind != "gltf") r.fail(where + ".kind", "unknown actor kind '" + kind + "' (expected gltf or blobtree)");
  if (act.kind == ActorKind::BlobTree) {
    if (!a.contains("blobtree")) {
      r.fail(where + ".blobtree", "missing (an actor of kind blobtree holds its tree here)");
    } else if (!r.failed()) {
      // Errors read "file: actor 'id': node 7 'thigh' (convSegment): ...".
      auto tree = blobTreeFromJson(a["blobtree"], sourceName + ": actor '" + act.id + "'");
      if (!tree) return Error{tree.error()};
      act.blobTree = std::move(*tree);
    }
  }
  act.assetPath = r.string(a, "asset", where, "", act.kind == ActorKind::Gltf);
  act.clip = r.integer(a, "clip", where, 0, 0, kMaxClipIndex);
  act.timeOffsetSec = r.number(a, "time_offset", where, 0.0);
  act.speed = r.number(a, "speed", where, 1.0);
  act.loop = r.boolean(a, "loop", where, true);
  act.visible = r.boolean(a, "visible", where, true);
  act.transform.translation = r.vec<3>(a, "translation", where, glm::vec3(0.0f));
  glm::vec4 q = r.vec<4>(a, "rotation", where, glm::vec4(0, 0, 0, 1));
  act.transform.rotation = glm::quat(q.w, q.x, q.y, q.z);
  act.transform.scale = r.vec<3>(a, "scale", where, glm::vec3(1.0f));
  if (r.failed()) return Status::success();
  if (act.id.empty()) r.fail(where + ".id", "must not be empty");
  else if (p.findActor(act.id)) r.fail(where + ".id", "duplicate id '" + act.id + "'");
  else if (glm::length(q) < 1e-6f) r.fail(where + ".rotation", "zero quaternion");
  else {
    // Only a quaternion that is not already unit is normalised: normalising a saved unit
    // quaternion again can move it by an ulp, and a project must reload as it was saved.
    if (std::abs(glm::length(q) - 1.0f) > 1e-5f) act.transform.rotation = glm::normalize(act.transform.rotation);
    p.actors.push_back(std::move(act));
  }
  return Status::success();
}

// The morph and the animorphosis, read after the actors they name.
Status readTransformations(const json& j, Project& p, const std::string& sourceName) {
  if (j.contains("morph")) {
    std::vector<std::string> ids;
    for (const Actor& a : p.actors) ids.push_back(a.id);
    auto morph = morphSetupFromJson(j["morph"], sourceName, ids);
    if (!morph) return Error{morph.error()};
    p.morph = std::move(*morph);
  }
  if (j.contains("animorphosis")) {
    auto a = animorphosisSetupFromJson(j["animorphosis"], sourceName);
    if (!a) return Error{a.error()};
    p.animorphosis = std::move(*a);
    if (Status s = checkAnimorphosis(p); !s) return Error{sourceName + ": " + s.error()};
  }
  return Status::success();
}

}  // namespace

Result<Project> projectFromJson(const std::string& text, const std::string& sourceName) {
  auto parsed = parseJsonText(text, sourceName);
  if (!parsed) return Error{parsed.error()};
  const json& j = *parsed;
  if (!j.is_object()) return Error{sourceName + ": expected a JSON object at the top level"};
  if (Status v = checkProjectVersion(j, sourceName); !v) return Error{v.error()};

  Reader r(sourceName);
  Project p;
  p.name = r.string(j, "name", "project", p.name);
  if (j.contains("timeline")) {
    if (!j["timeline"].is_object()) return Error{sourceName + ": timeline: expected an object"};
    readTimeline(j["timeline"], r, p.timeline);
  }
  if (j.contains("view")) {
    if (!j["view"].is_object()) return Error{sourceName + ": view: expected an object"};
    readView(j["view"], r, p.view);
  }
  if (j.contains("export")) {
    auto e = exportSettingsFromJson(j["export"], sourceName);
    if (!e) return Error{e.error()};
    p.exportSettings = std::move(*e);
  }
  if (j.contains("playblast")) {
    auto e = playblastSettingsFromJson(j["playblast"], sourceName);
    if (!e) return Error{e.error()};
    p.playblastSettings = std::move(*e);
  }
  if (j.contains("actors")) {
    const json& actors = j["actors"];
    if (!actors.is_array()) return Error{sourceName + ": actors: expected an array"};
    for (size_t i = 0; i < actors.size() && !r.failed(); ++i) {
      const std::string where = "actors[" + std::to_string(i) + "]";
      if (!actors[i].is_object()) {
        r.fail(where, "expected an object");
        break;
      }
      if (Status s = readActor(actors[i], where, r, p, sourceName); !s) return Error{s.error()};
    }
  }
  if (r.failed()) return Error{r.error()};
  if (Status s = readTransformations(j, p, sourceName); !s) return Error{s.error()};
  return p;
}

Result<Project> loadProject(const std::string& path, JobProgress* progress) {
  if (progress) progress->setStage("reading");
  auto text = readFile(path, kMaxReadFileBytes, progress);
  if (!text) return Error{text.error()};
  if (!progress) return projectFromJson(*text, path);
  const double parseSteps = 4.0 * double(text->size());
  progress->addTotal(parseSteps);
  if (progress->cancelled()) return jobCancelled();
  progress->setStage("parsing");
  auto p = projectFromJson(*text, path);
  progress->advance(parseSteps);
  return p;
}

Status saveProject(const Project& p, const std::string& path) { return writeFileAtomic(path, projectToJson(p)); }

}  // namespace animorph
