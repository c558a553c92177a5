#pragma once
// Counts a window's events (input, resize, expose, focus), so the frame loop
// knows whether anything happened since its last frame (RedrawPolicy). Call
// watchWindowEvents before ImGui's GLFW backend installs its callbacks: it
// keeps ours and calls them after its own.
#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace animorph {

void watchWindowEvents(GLFWwindow* window);
// Events counted so far (all watched windows).
uint64_t windowEventCount();
// Files dropped on a watched window since the last call (main thread).
std::vector<std::string> takeDroppedPaths();

}  // namespace animorph
