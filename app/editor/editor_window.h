#pragma once
// The editor's window and ImGui context: opened before the Vulkan side, closed after it.
#include "gpu/present/swapchain.h"

struct GLFWwindow;

namespace animorph {

// Opens a width x height window with no client API (Vulkan draws it), watches its events
// (window_events.h), creates ImGui's context with the editor's style. Returns null after a message
// on stderr when there is no display or no window.
GLFWwindow* openEditorWindow(int width, int height);

// The swapchain settings of the editor's window: cleared to the panels' colour; with bench, frames
// are presented at once (no vsync) so frame times measure the work.
gpu::SwapchainSettings editorSwapchainSettings(bool bench);

// Destroys ImGui's context and the window (after the Vulkan side is gone).
void closeEditorWindow(GLFWwindow* window);

}  // namespace animorph
