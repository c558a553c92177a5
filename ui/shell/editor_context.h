#pragma once
// What the app hands EditorUI each frame, and what it gets back.
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/export/playblast_job.h"
#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "core/math/bounds.h"
#include "core/scene/morph_runtime.h"
#include "core/scene/blob_guides.h"
#include "core/camera/camera.h"
#include "ui/common/status_bar.h"
#include "ui/viewport/viewport_input.h"
#include "ui/viewport/weight_paint_tool.h"

namespace animorph {

struct EditorContext {
  EditorContext(std::unique_ptr<Document>& doc, AssetCache& cache) : document(doc), assets(cache) {}
  // The open document. EditorUI replaces it on File > New / Open (then
  // EditorOutput::documentReplaced is set); a null pointer becomes a new
  // untitled document.
  std::unique_ptr<Document>& document;
  AssetCache& assets;
  FrameStats stats;    // filled by the app
  double nowSec = 0.0; // monotonic clock in seconds (autosave timing)
  double dtSec = 0.0;  // wall-clock seconds since the previous frame (playback)
  std::string viewportNote;  // shown after the frame number in the viewport (e.g. the morph stage)
  // The prepared morph the viewport shows (null: none); the morph panel shows its projection report.
  std::shared_ptr<const MorphRuntime> morphRuntime;
  // Optional: world bounds of the selection at a timeline time as the
  // renderer sees them (F frames them). Without it, EditorUI skins the
  // selection on the CPU.
  std::function<Bounds(const Document&, double timeSec)> selectionBounds;
  // File > Export > Playblast...: bakes and draws the frames into an .mp4 on the background job's
  // thread (the app gives the GPU layer's gpu::playblastProject, which makes a Vulkan device of its
  // own for it); null: the editor says a playblast needs the GPU renderer.
  PlayblastRunner playblast;
};

struct EditorOutput {
  ViewportRect viewport;                     // where to draw the 3D scene, window pixels
  OrbitCamera camera;                        // the camera to draw it with
  std::optional<PickRequest> pick;           // a click in the viewport to ray-cast
  std::optional<std::string> screenshotPath; // File > Save Screenshot chose this PNG path
  bool quit = false;                         // the user confirmed quitting
  bool documentReplaced = false;             // ctx.document is a different document now
  bool jobRunning = false;                   // a background job runs: keep drawing (its progress moves)
  bool weightPaintMode = false;              // Weight Paint mode: show weightOverlay.actorId alone, unmorphed
  WeightOverlayRequest weightOverlay;        // draw this actor in heat colours of these weights
  Selection highlightBlobNode;               // highlight this BlobTree node's skeleton (empty actorId: none)
  BlobGuides highlightChain;                 // highlight these lines (a chain hovered in Chain matching; empty: none)
};

}  // namespace animorph
