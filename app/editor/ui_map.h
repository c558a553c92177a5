#pragma once
// The map of named widgets and a little state that the editor writes for scripted GUI tests
// (ANIMORPH_UI_MAP=FILE; tests/gui/gui_driver.py reads it).
#include <string>

#include <nlohmann/json.hpp>

#include "core/doc/document.h"
#include "ui/shell/editor_ui.h"

namespace animorph {

// Writes the rectangles of named widgets, the document's state and `extra` to path, atomically.
void writeUiMap(const std::string& path, const WidgetRects& rects, const EditorOutput& out, const Document& doc,
                int frameCount, const nlohmann::json& extra);

// What the frame loop adds to the map after a frame.
struct FrameMapInfo {
  bool previewBusy = false;  // a preview is computing
  bool idle = false;         // the loop waits for input after this frame
  double polledAt = 0.0;     // CLOCK_MONOTONIC seconds when this frame took its input
  bool previewGpu = false;   // the preview shown is the GPU's
  std::string presentPath;   // how frames reach the window
  bool particlesShown = false;  // some BlobTree was drawn as particles (editor/particle_view.h)
  bool paced = false;           // scrubbing while a CPU preview computes: the loop is paced (scene/scrub_pacing.h)
  int scenePasses = 0;          // frames so far that rendered the 3D scene
  int keptFrames = 0;           // frames so far that showed the kept viewport image of an unchanged scene
};

// writeUiMap with the editor's state: the status line, the preview line, the stand-in segment.
void writeEditorUiMap(const std::string& path, const EditorUI& ui, EditorContext& ectx, int frameCount,
                      const FrameMapInfo& info);

}  // namespace animorph
