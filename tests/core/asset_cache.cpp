#include <catch2/catch.hpp>

#include <filesystem>

#include "demo/dense.h"
#include "demo/gear.h"
#include "core/project/asset_cache.h"
#include "core/io/gltf_export.h"
#include "util/temp_dir.h"

using namespace animorph;

TEST_CASE("asset cache loads once, remembers failures, reloads changed files", "[doc][assets]") {
  test::TempDir tmp;
  const std::string path = tmp.file("a.glb");
  REQUIRE(exportGlb(makeDenseCharacter(500), path).ok());
  AssetCache cache;
  const auto& first = cache.get(path);
  REQUIRE(first.character);
  CHECK(first.error.empty());
  const auto* loaded = first.character.get();
  CHECK(cache.get(path).character.get() == loaded);  // not reloaded
  CHECK(cache.refresh() == 0);

  const auto& missing = cache.get(tmp.file("missing.glb"));
  CHECK_FALSE(missing.character);
  CHECK(missing.error.find("missing.glb") != std::string::npos);

  // Replace the file with another character and move its time forward.
  REQUIRE(exportGlb(makeGearCharacter(), path).ok());
  std::filesystem::last_write_time(path, std::filesystem::last_write_time(path) + std::chrono::seconds(5));
  CHECK(cache.refresh() == 1);
  REQUIRE(cache.get(path).character);
  CHECK(cache.get(path).character->meshes[0].name == "gear");
  cache.clear();
  CHECK(cache.get(path).character->meshes[0].name == "gear");
}
