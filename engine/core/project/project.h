#pragma once
// The saved state of a project (*.animorph): actors, timeline, view options.
// Plain data; the Document owns it and edits it only through Commands.
#include <string>
#include <vector>

#include "core/anim/timeline.h"
#include "core/blobtree/blob_tree.h"
#include "core/project/animorphosis_setup.h"
#include "core/project/export_settings.h"
#include "core/project/playblast_settings.h"
#include "core/project/morph_setup.h"
#include "core/math/transform.h"

namespace animorph {

inline constexpr int kProjectFormatVersion = 1;

// What an actor shows: a glTF character (assetPath, clip) or an animated
// BlobTree held in the project itself (blobTree).
enum class ActorKind { Gltf, BlobTree };

// A character placed in the scene, playing one of its clips.
struct Actor {
  std::string id;         // stable, unique in the project
  std::string name;
  ActorKind kind = ActorKind::Gltf;
  std::string assetPath;  // glTF path, relative to the project file's directory (Gltf actors)
  BlobTree blobTree;      // the shape of a BlobTree actor (unused for Gltf actors)
  int clip = 0;           // index into the asset's clips; ignored when it has none
  double timeOffsetSec = 0.0;  // clip time = (t - timeOffsetSec) * speed
  double speed = 1.0;
  bool loop = true;
  bool visible = true;
  Transform transform;
  bool operator==(const Actor&) const = default;
};

struct ViewOptions {
  bool showGrid = true;
  bool showSkeleton = true;
  bool wireframe = false;
  bool showAxes = true;
  bool showStandins = false;  // morph actors' stand-in capsules over the meshes
  bool operator==(const ViewOptions&) const = default;
};

struct Project {
  std::string name = "untitled";
  std::vector<Actor> actors;
  Timeline timeline;
  ViewOptions view;
  MorphSetup morph;  // the source -> target morph; disabled when morph.sourceActorId is empty
  AnimorphosisSetup animorphosis;  // BlobTree -> BlobTree animorphosis; disabled when its source is empty
  ExportSettings exportSettings;   // File > Export...: the last settings used
  PlayblastSettings playblastSettings;  // File > Export > Playblast...: the last settings used
  bool operator==(const Project&) const = default;

  Actor* findActor(const std::string& id);
  const Actor* findActor(const std::string& id) const;
  // An id not used by any actor, built from base ("actor" -> "actor_2").
  std::string uniqueActorId(const std::string& base) const;
  // A display name no actor has, built from base as outliners do ("Blob" -> "Blob 2"; a name that
  // already ends in a number counts on from it: "Blob 2" -> "Blob 3").
  std::string uniqueActorName(const std::string& base) const;
};

}  // namespace animorph
