#pragma once
// Drives EditorUI headless: a real ImGui context (font atlas built, no
// renderer backend), input injected through ImGuiIO the way the GLFW
// backend of ImGui 1.86 writes it (KeyMap/KeysDown with GLFW key codes,
// MousePos/MouseDown, KeyCtrl/Shift/Alt, text characters).
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "ui/shell/editor_ui.h"

namespace animorph::test {

class EditorHarness {
 public:
  // prefsPath: where the EditorUI keeps its preferences (a temp file).
  explicit EditorHarness(const std::string& prefsPath, glm::vec2 display = {1280.0f, 800.0f});
  ~EditorHarness();
  EditorHarness(const EditorHarness&) = delete;
  EditorHarness& operator=(const EditorHarness&) = delete;

  // Runs n frames of dtSec each (the wall clock advances by dtSec too).
  void frames(int n = 1, double dtSec = 1.0 / 60.0);

  // Mouse. click, doubleClick and drag first let the double-click time pass
  // (one frame of 0.35 s), as a person's separate gestures would.
  void settle();
  void moveTo(glm::vec2 p);  // sets the position and runs a frame
  void press(int button = 0);
  void release(int button = 0);
  void click(glm::vec2 p, int button = 0);
  void doubleClick(glm::vec2 p);
  // Press at from, move to `to` in steps, release.
  void drag(glm::vec2 from, glm::vec2 to, int button = 0, int steps = 6);
  void wheel(glm::vec2 p, float notches);

  // Keyboard: key is a GLFW key code.
  void setModifiers(bool ctrl, bool shift = false, bool alt = false);
  void tapKey(int key, bool ctrl = false, bool shift = false, bool alt = false);
  void type(const std::string& utf8);

  // Named widget from the last frame (fails the test when absent).
  glm::vec2 widgetCenter(const std::string& key) const;
  bool hasWidget(const std::string& key) const { return ui->widgets().find(key).has_value(); }
  void clickWidget(const std::string& key) { click(widgetCenter(key)); }

  Document& doc() { return *document; }

  std::unique_ptr<Document> document;
  AssetCache assets;
  std::unique_ptr<EditorUI> ui;
  EditorContext ctx;
  double nowSec = 100.0;
  // true: each frame waits for the background job it started (frame by frame, deterministic);
  // false: jobs run on across frames, as in the editor (a test that cancels one).
  bool finishJobs = true;

 private:
  void frame(double dtSec);
  struct ImGuiContext* imgui_ = nullptr;
};

}  // namespace animorph::test
