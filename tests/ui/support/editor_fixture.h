#pragma once
// A temp directory, an EditorHarness keeping its preferences there, and
// helpers to build projects with the test character.
#include <string>

#include "support/test_character.h"
#include "support/ui_harness.h"
#include "util/temp_dir.h"

namespace animorph::test {

// The document's first BlobTree actor, or null.
inline const Actor* blobActor(EditorHarness& h) {
  for (const auto& a : h.doc().project().actors)
    if (a.kind == ActorKind::BlobTree) return &a;
  return nullptr;
}

struct EditorFixture {
  TempDir dir;
  EditorHarness h;

  // display: the window size in pixels.
  explicit EditorFixture(glm::vec2 display = {1280.0f, 800.0f}) : h(dir.file("config/prefs.json"), display) {
    h.ui->state().prefs.autosaveIntervalSec = 0.0;  // tests opt in
  }

  // Writes hero.gltf into the temp dir and opens a document "scene.animorph" in that dir with one actor
  // "hero" using it (not saved to disk). Returns the character.
  Character loadHeroScene() {
    std::string asset = dir.file("hero.gltf");
    Character c = writeTestCharacter(asset);
    Project p;
    Actor a;
    a.id = "hero";
    a.name = "hero";
    a.assetPath = "hero.gltf";
    p.actors.push_back(a);
    h.document->reset(p, dir.file("scene.animorph"));
    h.frames(1);
    return c;
  }

  // loadHeroScene plus a second actor "other" of the same asset and a morph
  // hero -> other (markers 10, 20, 30, 40; no morph.actors entries), nothing selected.
  void loadHeroMorphScene() {
    loadHeroScene();
    Project p = h.doc().project();
    Actor b = p.actors[0];
    b.id = "other";
    p.actors.push_back(b);
    p.morph.sourceActorId = "hero";
    p.morph.targetActorId = "other";
    p.morph.markers = {10, 20, 30, 40};
    h.document->reset(p, dir.file("scene.animorph"));
    h.doc().selection = {};
    h.frames(2);
  }
};

}  // namespace animorph::test
