#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

#include "ui/common/prefs.h"
#include "util/temp_dir.h"

using namespace animorph;

TEST_CASE("preferences round trip through the file", "[prefs]") {
  test::TempDir dir;
  std::string path = dir.file("nested/animorph/prefs.json");
  Preferences p;
  p.outlinerWidth = 301.5f;
  p.inspectorWidth = 280.0f;
  p.timelineHeight = 190.0f;
  p.cameraScheme = CameraScheme::Blender;
  p.otherSchemeToo = false;
  p.autosaveIntervalSec = 30.0;
  p.particleView = false;
  for (int i = 0; i < 10; ++i) addRecentFile(p, "/projects/p" + std::to_string(i) + ".animorph");
  addRecentFile(p, "/projects/p5.animorph");
  REQUIRE(p.recentFiles.size() == kMaxRecentFiles);
  CHECK(p.recentFiles.front() == "/projects/p5.animorph");
  CHECK(std::count(p.recentFiles.begin(), p.recentFiles.end(), "/projects/p5.animorph") == 1);
  REQUIRE(savePreferences(p, path).ok());
  auto back = loadPreferences(path);
  REQUIRE(back.ok());
  CHECK(*back == p);
}

TEST_CASE("missing preferences give defaults, broken ones an error naming the key", "[prefs]") {
  test::TempDir dir;
  auto none = loadPreferences(dir.file("absent.json"));
  REQUIRE(none.ok());
  CHECK(*none == Preferences{});

  std::string path = dir.file("prefs.json");
  auto write = [&](const std::string& text) { std::ofstream(path) << text; };
  write("{ not json");
  auto bad = loadPreferences(path);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("prefs.json") != std::string::npos);
  CHECK(bad.error().find("not valid JSON") != std::string::npos);

  write(R"({"layout": {"outlinerWidth": "wide"}})");
  bad = loadPreferences(path);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("layout.outlinerWidth") != std::string::npos);

  write(R"({"camera": {"scheme": "houdini"}})");
  bad = loadPreferences(path);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("camera.scheme") != std::string::npos);

  write(R"({"recentFiles": ["/a", 3]})");
  bad = loadPreferences(path);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("recentFiles[1]") != std::string::npos);

  write(R"({"autosaveIntervalSec": -5})");
  bad = loadPreferences(path);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("prefs.json: autosaveIntervalSec: out of range") != std::string::npos);

  write(R"({"particleView": "yes"})");
  bad = loadPreferences(path);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("particleView: expected true or false") != std::string::npos);

  // Unknown keys (from a newer version) and partial files are fine.
  write(R"({"future": 1, "camera": {"scheme": "blender"}})");
  auto partial = loadPreferences(path);
  REQUIRE(partial.ok());
  CHECK(partial->cameraScheme == CameraScheme::Blender);
  CHECK(partial->outlinerWidth == Preferences{}.outlinerWidth);
}

TEST_CASE("preferences path follows XDG_CONFIG_HOME", "[prefs]") {
  const char* old = std::getenv("XDG_CONFIG_HOME");
  std::string saved = old ? old : "";
  ::setenv("XDG_CONFIG_HOME", "/tmp/xdg-test", 1);
  CHECK(defaultPreferencesPath() == "/tmp/xdg-test/animorph/prefs.json");
  ::setenv("XDG_CONFIG_HOME", "relative/ignored", 1);
  CHECK(defaultPreferencesPath().find("/.config/animorph/prefs.json") != std::string::npos);
  if (old) ::setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
  else ::unsetenv("XDG_CONFIG_HOME");
}
