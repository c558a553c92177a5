#pragma once
// The map of named widgets and a little state that the editor writes for scripted GUI tests
// (ANIMORPH_UI_MAP=FILE; tests/gui/gui_driver.py reads it).
#include <string>

#include <nlohmann/json.hpp>

#include "doc/document.h"
#include "editor_ui.h"

namespace animorph {

// Writes the rectangles of named widgets, the document's state and `extra` to path, atomically.
void writeUiMap(const std::string& path, const WidgetRects& rects, const EditorOutput& out, const Document& doc,
                int frameCount, const nlohmann::json& extra);

}  // namespace animorph
