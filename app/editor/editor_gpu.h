#pragma once
// The editor's Vulkan side: the device, the swapchain, the renderers and the GPU caches and
// previews, made together and, after a lost device, remade together (docs/rendering.md, "A lost
// device"). The document, the UI state and ImGui's context live outside and survive.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "gpu/polygonizer/blob_preview_set.h"
#include "core/doc/document.h"
#include "gpu/vulkan/context.h"
#include "gpu/polygonizer/implicit_preview.h"
#include "gpu/present/imgui_vulkan.h"
#include "gpu/render/mesh_cache.h"
#include "gpu/render/scene_renderer.h"
#include "gpu/render/standin_binding_cache.h"
#include "gpu/present/swapchain.h"
#include "gpu/present/viewport_image.h"
#include "core/camera/camera.h"
#include "ui/viewport/viewport_input.h"

struct GLFWwindow;

namespace animorph {

struct EditorGpu {
  // Destroyed in reverse: previews and caches, then the renderers, the swapchain, the device.
  std::unique_ptr<gpu::Context> ctx;
  std::unique_ptr<gpu::Swapchain> swapchain;
  std::unique_ptr<gpu::SceneRenderer> renderer;
  std::unique_ptr<ImGuiVulkan> imgui;  // needs ImGui's context
  // The viewport's kept image (null: the scene is drawn into every frame, ANIMORPH_VIEWPORT_IMAGE=off)
  // and the fingerprint of the scene it holds (nullopt: none, or one that must be drawn every frame).
  std::unique_ptr<gpu::ViewportImage> viewportImage;
  std::optional<uint64_t> viewportFingerprint;
  std::unique_ptr<gpu::MeshCache> meshes;
  std::unique_ptr<gpu::BlobPreviewSet> blobPreviews;
  std::unique_ptr<gpu::StandinBindingCache> standinBindings;
  std::unique_ptr<gpu::ImplicitPreview> morphPreview;  // the morph's B->C stage
};

// Errors: no usable device ("no usable Vulkan device: ..."), or what failed to be made.
Result<std::unique_ptr<EditorGpu>> createEditorGpu(GLFWwindow* window, const gpu::SwapchainSettings& settings);

// After gpu::deviceLost() (a driver reset, a GPU removed): the device is gone with everything made on
// it. Saves the work (the autosave), then remakes the whole Vulkan side into gpuSide; the document,
// the UI and its state stay as they are. Returns the status bar's line; an error (said on stderr
// too) when no device can be made, gpuSide then null.
Result<std::string> recoverLostDevice(GLFWwindow* window, const gpu::SwapchainSettings& settings, Document& doc,
                                      double nowSec, std::unique_ptr<EditorGpu>& gpuSide);

// Records the 3D scene into the viewport's rectangle of the window (window pixels, scaled to the
// framebuffer) and the UI over it, and presents. With a kept viewport image the scene is rendered
// into it only when its fingerprint changed (gpu/render/scene_fingerprint.h), and the image is
// copied under the UI. A capture requested from the swapchain this frame is written to capturePath
// as PNG; captured says it was taken.
struct PresentedFrame {
  gpu::FrameStatus status = gpu::FrameStatus::Failed;
  bool captured = false;
  bool scenePass = false;   // the 3D scene was rendered this frame
  bool sceneKept = false;   // the viewport showed the kept image of an unchanged scene instead
};
PresentedFrame presentFrame(EditorGpu& g, const ViewportRect& viewport, const OrbitCamera& camera,
                            const gpu::Scene& scene, const std::string& capturePath);

}  // namespace animorph
