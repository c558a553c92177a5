#pragma once
// A temp directory, an EditorHarness keeping its preferences there, and
// helpers to build projects with the test character.
#include <string>

#include "support/test_character.h"
#include "support/ui_harness.h"
#include "util/temp_dir.h"

namespace animorph::test {

struct EditorFixture {
  TempDir dir;
  EditorHarness h{dir.file("config/prefs.json")};

  EditorFixture() { h.ui->state().prefs.autosaveIntervalSec = 0.0; }  // tests opt in

  // Writes hero.gltf into the temp dir (registered for the tests' asset
  // cache) and opens a document "scene.animorph" in that dir with one actor
  // "hero" using it (not saved to disk). Returns the character.
  Character loadHeroScene() {
    std::string asset = dir.file("hero.gltf");
    Character c = writeTestCharacter(asset);
    registerCharacter(asset, c);
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
};

}  // namespace animorph::test
