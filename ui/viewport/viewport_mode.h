#pragma once
// What a left click and drag do in the viewport: select and move objects, or
// edit the selected morph actor's stand-in segments (standin_tool.h).
namespace animorph {

enum class ViewportMode { Object, StandinEdit };

inline const char* viewportModeName(ViewportMode m) {
  switch (m) {
    case ViewportMode::Object: return "Object";
    case ViewportMode::StandinEdit: return "Stand-in edit";
  }
  return "";
}

}  // namespace animorph
