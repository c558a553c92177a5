#pragma once
// Counts a window's events (input, resize, expose, focus), so the frame loop
// knows whether anything happened since its last frame (RedrawPolicy). Call
// watchWindowEvents before ImGui's GLFW backend installs its callbacks: it
// keeps ours and calls them after its own.
#include <cstdint>

struct GLFWwindow;

namespace animorph {

void watchWindowEvents(GLFWwindow* window);
// Events counted so far (all watched windows).
uint64_t windowEventCount();

}  // namespace animorph
