#pragma once
// The editor's preview of one implicit shape (a BlobTree actor, the morph's
// B->C stage), polygonised off the UI thread, on the CPU or the GPU:
//  * CPU: a PreviewPolygonizer worker answers each shape at the interactive
//    resolution, then at the refined one; a newer shape cancels the run in
//    progress. The newest mesh is uploaded when it arrives.
//  * GPU: GpuPolygonizer::record() on this preview's own command buffers,
//    submitted to the queue before the frame that draws it (same queue, so the
//    frame sees the result; no CPU read-back, nothing waits). While the shape
//    changes every frame it runs at the interactive resolution; once a frame
//    repeats the shape, at the refined one, recorded once: when that record has
//    completed, its counters say whether it fitted and the preview goes quiet
//    (a buffer overflow is grown and redone first).
//    Where polygonising every frame would hold the editor below 30 fps (a
//    frame took longer than 1/30 s and recorded a new shape), the next new
//    shape waits one frame and the viewport keeps the last mesh, as it does
//    while the CPU worker runs: the UI stays responsive and the preview shows
//    every other shape. On a fast GPU frames stay within the budget and every
//    frame's shape is polygonised. A kind of shape whose pipelines are not
//    compiled yet (~1 s on lavapipe) does not stall the frame: they compile in
//    the background and the CPU worker draws the shape meanwhile.
//    The shape's field (PreviewSource::field: the tree flattened into one
//    program; 58 ms for the animorphosis demo's 7,300-node C(t) on an H100's
//    host) compiles on a thread of its own (PreviewFieldCompiler, latest request
//    wins): the frame records the newest field compiled since the last record,
//    this shape's or an older one's, and meanwhile keeps drawing the last mesh.
//    A field measured cheaper than kCompileHereMs compiles in the frame itself
//    (a frame's delay would cost more); a screenshot (settle) compiles it there.
//    A record whose slot's record before is still on the GPU waits for the next
//    frame: the UI thread does not wait for the GPU either.
// Any GPU failure (unsupported field, out of memory, device errors) moves this
// preview to the CPU worker and says why (status().gpuFallback); a field the
// GPU cannot express moves only that shape. The viewport always shows the
// newest finished mesh.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/vulkan/context.h"
#include "gpu/render/gpu_mesh.h"
#include "gpu/polygonizer/preview_field_compiler.h"
#include "core/poly/preview_polygonizer.h"
#include "gpu/render/scene_renderer.h"
#include "shared_constants.h"
#include "core/poly/preview_device.h"

namespace animorph::gpu {

class GpuPolygonizer;
struct GpuField;
struct GpuPolygonizeSettings;

struct ImplicitPreviewSettings {
  int interactiveResolution = 96;  // while the shape changes (scrubbing, playing, editing)
  int refinedResolution = 128;     // once it stops changing
  bool gpu = false;                // polygonise on the GPU (else, or after a GPU failure, the CPU worker)
  int threads = 0;                 // CPU worker threads (0: all)
  bool settle = false;             // GPU: go straight to the refined resolution (screenshots)
  bool paceGpu = true;             // GPU: skip a frame's new shape after a slow frame that recorded one (see above)
};

struct ImplicitPreviewStatus {
  bool hasMesh = false;       // something was polygonised (an empty shape has no triangles)
  bool gpu = false;           // the mesh on screen came from the GPU
  int resolution = 0;         // of the mesh on screen
  double milliseconds = 0.0;  // its polygonisation time (GPU: submit to completion, seen from the frame loop)
  double timeSec = -1.0;      // the scene time of the mesh drawn (-1: none yet; GPU: of the last recorded shape)
  size_t triangles = 0;
  bool refining = false;      // a finer mesh of the current shape is on its way
  bool compiling = false;     // GPU: the pipelines for this kind of shape are compiling (the CPU worker fills in)
  std::string error;          // the shape could not be polygonised
  std::string gpuFallback;    // why this preview left the GPU for the CPU ("" when it did not)
};

// Auto/GPU/CPU preference on a device of type deviceType: whether to use the
// GPU, and a short reason for the status bar ("GPU: auto, discrete GPU").
struct PreviewBackend {
  bool gpu = false;
  std::string why;
};
// What a preview polygonises, for Auto on CPU devices (lavapipe): a morph of two convolution
// stand-ins runs the GPU path's line groups, which scrub faster in the editor than the CPU worker
// there (`bench editor`: ~34-41 ms against ~47-51 ms a frame at 1600x900, 96^3); BlobTrees and
// capsule stand-ins run the per-point interpreter, several times slower than the worker there
// (`bench gpu`, blob creature row). A morph whose sides have colours counts as Other: the GPU path
// colours it by walking its whole colour program at every vertex (docs/gpu-polygonizer.md,
// "Colour"), ~5x the morph's own polygonisation there (`bench gpu-color`, demo morph rows: 624 ms
// against the worker's 88 ms at 96^3 on lavapipe, 2026-11-29).
enum class PreviewWork { ConvolutionMorph, Other };
PreviewBackend choosePreviewBackend(PreviewDevice preference, VkPhysicalDeviceType deviceType,
                                    PreviewWork work = PreviewWork::Other);

// The status bar's line: "preview 128^3 CPU 41 ms, 23110 tris (refining) | CPU (auto: ...)",
// with the error or the GPU fallback when there is one.
std::string describePreviewStatus(const ImplicitPreviewStatus& st, const PreviewBackend& backend);

class ImplicitPreview {
 public:
  explicit ImplicitPreview(Context& ctx);
  ~ImplicitPreview();  // cancels the worker, waits for the GPU work of this preview
  ImplicitPreview(const ImplicitPreview&) = delete;
  ImplicitPreview& operator=(const ImplicitPreview&) = delete;

  // Once per frame while the shape is shown: source (an immutable snapshot;
  // sameAs decides whether it changed). CPU: submits to the worker, uploads a
  // finished mesh. GPU: records and submits when there is something to do.
  void update(std::shared_ptr<const PreviewSource> source, double timeSec, const ImplicitPreviewSettings& s);
  // Before the shape is first shown: compiles, in the background, the GPU pipelines shapes like
  // source need (GpuPolygonizer::prewarm), so the frame that first shows one does not stall on
  // the compiler. Nothing when s does not ask for the GPU or it failed before.
  void prewarm(const PreviewSource& source, const ImplicitPreviewSettings& s);
  // Appends the newest mesh to scene (nothing before the first one).
  void draw(Scene& scene, const glm::mat4& model, const glm::vec4& color, bool selected) const;
  // The newest CPU result (picking, tests); null on the GPU path.
  std::shared_ptr<const PreviewResult> cpuResult() const { return usingGpu() && !cpuFillIn_ ? nullptr : result_; }
  ImplicitPreviewStatus status() const;
  // True while a finer or newer mesh of the current shape is on its way.
  bool busy() const;
  // True while only more frames move it on (GPU refinement, a CPU result to upload); false
  // while it waits for the CPU worker alone, which wakes the frame loop when it publishes.
  bool needsFrames() const;
  // Waits until the current shape is fully answered (CPU worker idle and its
  // mesh uploaded; GPU work complete), at most timeoutSec. Returns idle.
  bool waitIdle(double timeoutSec);
  // Once per frame after the frame's submit: frees meshes no frame in flight uses.
  void endFrame();
  // Why the GPU path was given up ("" while it works or was never used).
  const std::string& gpuFailure() const { return gpuFailure_; }
  // GPU polygonisations recorded so far (tests, benches).
  uint64_t gpuRecordCount() const { return serial_; }
  // Forgets a GPU failure (the user switched devices): the next update tries the GPU again.
  void clearGpuFailure() { gpuFailure_.clear(); }
  // The GPU path's field compiles so far: where they ran and how long they took (benches, tests).
  PreviewFieldCounters fieldCounters() const { return compiler_ ? compiler_->counters() : PreviewFieldCounters{}; }
  // GPU records (and screenshots' polygonisations) that prepared their frame's host half on this
  // thread because the compiled field brought none that suited (GpuPolygonizer::preparesInRecord).
  uint64_t gpuPreparesInRecord() const;
  // GPU records whose loops the device cut and that were redone sparing it more instead of leaving
  // the GPU (GpuPolygonizer::cutFramesRedone; lavapipe's loop limiter).
  uint64_t gpuCutFramesRedone() const;

 private:
  bool usingGpu() const { return gpuActive_; }
  void updateCpu(std::shared_ptr<const PreviewSource> source, double timeSec, const ImplicitPreviewSettings& s);
  // Returns false (and sets gpuFailure_ or fieldFallback_) when the GPU cannot take this shape.
  bool updateGpu(const std::shared_ptr<const PreviewSource>& source, double timeSec, const ImplicitPreviewSettings& s);
  // updateGpu's steps. What one call asks for: whether the frame before asked for this shape
  // too, whether it is the shape recorded last, and the resolution to show it at.
  struct GpuAsk {
    bool repeated = false;
    bool sameShape = false;
    int res = 0;
    double frameSec = 0.0;      // wall time since the last updateGpu
    bool recordedLast = false;  // the last updateGpu recorded a polygonisation
  };
  // Notes the shape against the ones asked for before (repeats, the refinement hold, the pacing
  // clock) and resets the per-call flags.
  GpuAsk askGpu(const std::shared_ptr<const PreviewSource>& source, const ImplicitPreviewSettings& s);
  // The shape just recorded, asked for again: true while its record runs or once it fitted
  // (settled_), false when the GPU failed; nullopt: record it again (it overflowed).
  std::optional<bool> lastRecordSettles();
  // A field not compiled yet (true: the last mesh stays), or one that failed (false for this shape:
  // the CPU worker draws it; true for an older shape's); nullopt when field can be recorded.
  std::optional<bool> unusableField(const std::shared_ptr<const CompiledPreviewField>& field,
                                    const std::shared_ptr<const PreviewSource>& source);
  // A screenshot (settle): waits for this preview's records, then polygonises synchronously until
  // the mesh fits. Returns false when the GPU failed (gpuFailure_ says why).
  bool polygonizeNow(const GpuField& gf, const GpuPolygonizeSettings& gs,
                     const std::shared_ptr<const CompiledPreviewField>& field,
                     const std::shared_ptr<const PreviewSource>& source, int res, double timeSec);
  // Records the polygonisation into this frame's slot and submits it (defers while the GPU still
  // holds the slot). Returns false when the GPU failed (gpuFailure_ says why).
  bool submitRecord(const GpuField& gf, const GpuPolygonizeSettings& gs,
                    const std::shared_ptr<const CompiledPreviewField>& field,
                    const std::shared_ptr<const PreviewSource>& source, int res);
  // The field to record for source at res: this shape's if compiled, else the newest compiled
  // since the last record (an older shape's), else null (its compile is under way). settle: this
  // shape's, compiled now.
  std::shared_ptr<const CompiledPreviewField> takeField(const std::shared_ptr<const PreviewSource>& source, int res,
                                                        double timeSec, bool settle);
  // field was recorded or dropped: fields compiled before it are not shown any more.
  void fieldTaken(const std::shared_ptr<const CompiledPreviewField>& field);
  Status initGpu();
  void pollGpu();
  void uploadNew();
  void endCpuFillIn();

  Context& ctx_;
  // CPU path
  std::unique_ptr<PreviewPolygonizer> worker_;
  uint64_t uploadedSerial_ = 0;
  std::shared_ptr<const PreviewResult> result_;
  std::unique_ptr<GpuMesh> mesh_;
  std::vector<std::pair<uint64_t, std::unique_ptr<GpuMesh>>> retired_;  // (frame retired, mesh)
  uint64_t frame_ = 0;
  std::string uploadError_;
  // GPU path
  bool gpuActive_ = false;    // the last update used the GPU
  std::string gpuFailure_;    // sticky: the GPU failed for this preview
  std::string fieldFallback_; // this shape only: the GPU cannot express it
  std::unique_ptr<GpuPolygonizer> poly_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmds_[kFramesInFlight]{};
  VkFence fences_[kFramesInFlight]{};
  double submittedAt_[kFramesInFlight]{};
  int submittedRes_[kFramesInFlight]{};
  bool pending_[kFramesInFlight]{};
  uint64_t serial_ = 0;  // submissions so far
  std::shared_ptr<const PreviewSource> gpuSource_;
  int gpuResolution_ = 0;   // of the shape recorded last
  int recordsOfShape_ = 0;  // records in a row of (gpuSource_, gpuResolution_)
  bool settled_ = false;    // a record of this shape was read back without overflow: no more records
  bool gpuDrawable_ = false;
  int gpuShownRes_ = 0;
  double gpuDrawnTime_ = -1.0;      // scene time of the last recorded shape (what the next draw shows)
  double lastUpdateAt_ = 0.0;      // wall clock of the last updateGpu (frame pacing)
  bool lastUpdateRecorded_ = false;  // it recorded a polygonisation
  bool deferred_ = false;            // a new shape waits for the next frame
  // A shape asked for again is refined at once, unless the one before it lasted less than
  // kInteractionSec (a drag): then once it has held still for kRefineDelaySec (updateGpu).
  static constexpr double kInteractionSec = 0.3, kRefineDelaySec = 0.15;
  double shapeSince_ = -1e9;         // wall clock when the shape now asked for first was
  double previousShapeLasted_ = 1e9; // how long the shape before it was asked for
  bool refineHeld_ = false;          // a repeated shape waits (still dragging?) before it is refined
  bool compiling_ = false;           // the shape waits for its pipelines (GpuPolygonizer::ready)
  bool cpuFillIn_ = false;           // meanwhile the CPU worker polygonises it (mesh_, result_ are its)
  // The field compiles (takeField). A field that took less than kCompileHereMs last time compiles
  // on the UI thread; a preview's first field is waited for up to kFirstFieldWaitSec.
  static constexpr double kCompileHereMs = 2.0, kFirstFieldWaitSec = 0.1;
  std::unique_ptr<PreviewFieldCompiler> compiler_;       // made on the first field the GPU path needs
  std::shared_ptr<const PreviewSource> lastAsked_;       // the shape the last updateGpu asked for
  std::shared_ptr<const CompiledPreviewField> ready_;    // compiled, not recorded yet
  std::shared_ptr<const CompiledPreviewField> recordedField_;  // of gpuSource_ (records it again on overflow)
  std::shared_ptr<const PreviewSource> fieldFailed_;     // its field failed, or the GPU cannot express it
  uint64_t takenFieldId_ = 0;  // the newest field recorded or dropped
  double lastFieldMs_ = -1.0;  // the last field's compile time (-1: none yet)
  bool fieldPending_ = false;  // the shape asked for waits for its field
  double gpuShownMs_ = 0.0;
};

}  // namespace animorph::gpu
