#pragma once
// Interactive preview of an animated BlobTree (docs/design.md §6: "the editor
// refines progressively while scrubbing stops"). A worker thread polygonises
// the latest request only: a new request cancels the run in progress (the
// polygoniser's cancel flag) and replaces any request still waiting. Each
// request is answered first at a coarse resolution, then, if no newer request
// came in meanwhile, at the fine one. The UI thread submits and polls; it
// never waits. Each level keeps the last frame (PolygonizeHistory): while
// scrubbing, blocks the field provably left almost unchanged are reused. A request previews a BlobTree, or any other PreviewSource (the
// morph's B->C stage: scene/morph_preview_source.h).
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/blobtree/blob_tree.h"
#include "core/poly/polygonizer.h"

namespace animorph {

// A preview's field as one program, for polygonisers other than the worker's
// (the GPU's): the program and the grid bounds (nullopt: the program's own).
struct PreviewField {
  FieldProgram program;  // empty when pooledProgram is set
  std::optional<Bounds> bounds;
  // Solid noise moving the polygonised mesh's vertices along their normals (the morph's noise
  // track, displaceBySolidNoise): amplitude (m), frequency (1/m); 0 amplitude: none.
  float noiseAmplitude = 0.0f;
  float noiseFrequency = 1.0f;
  // The program whose colours the surface takes when it is not program's own (a morph's stand-ins
  // split into their colour samples, MorphImplicitField::colorProgram); null: program's.
  std::shared_ptr<const FieldProgram> colorProgram;
  // How program was made where its source refills a kept structure (the animorphosis' C(t),
  // FieldProgram::finishRefill): Refilled when only its values were computed; nullopt: compiled afresh.
  std::optional<RefillOutcome> refill;
  // The program when its source lends one from a pool it reuses once nobody holds it (the
  // animorphosis' C(t), SharedGenericCompiler::takeProgram); null: program, held by value.
  std::shared_ptr<FieldProgram> pooledProgram;
  // The field's program: pooledProgram's when set, else program.
  const FieldProgram& fieldProgram() const { return pooledProgram ? *pooledProgram : program; }
};

// A shape to preview: an immutable snapshot (shared with the worker thread).
class PreviewSource {
 public:
  virtual ~PreviewSource() = default;
  // True when other shows the same shape (resubmitting it changes nothing).
  virtual bool sameAs(const PreviewSource& other) const = 0;
  // Checked once per request before polygonising; the error is published as the result's.
  virtual Status validate() const { return {}; }
  // Polygonises at resolution (cells along the longest side) with threads;
  // *cancel turning true stops it early (result.cancelled). history (may be null): the worker's
  // temporal coherence for this resolution, which a source may use (BlobTree sources do: scrubbing
  // reuses the blocks the last frame's field provably left within kPreviewReuseToleranceCells).
  // Errors: polygoniser errors.
  virtual Result<PolygonizeResult> polygonize(int resolution, int threads, const std::atomic<bool>* cancel,
                                              PolygonizeHistory* history) const = 0;
  // The same shape as one program at resolution. Errors: what one program
  // cannot express (the caller polygonises with polygonize() instead).
  virtual Result<PreviewField> field(int resolution) const = 0;
};

// How far (in cells) a preview's vertex may be from a full re-polygonisation's when the worker
// reuses the previous frame's blocks (PolygonizeSettings::reuseToleranceCells).
inline constexpr float kPreviewReuseToleranceCells = 0.1f;

// How a preview polygonises one program (BlobTree sources, the animorphosis' C(t)): with the
// worker's history, on the last frame's grid while the shape fits in it, its blocks reused; with
// the primitives' colours as vertex colours (field/surface_color.h), drawn by the viewport.
Result<PolygonizeResult> polygonizePreviewProgram(const FieldProgram& program, int resolution, int threads,
                                                  const std::atomic<bool>* cancel, PolygonizeHistory* history);

// A BlobTree at a tree time as a PreviewSource.
std::shared_ptr<const PreviewSource> blobTreePreviewSource(std::shared_ptr<const BlobTree> tree, double timeSec);

struct PreviewRequest {
  std::shared_ptr<const BlobTree> tree;  // a snapshot: never modified after submission
  std::shared_ptr<const PreviewSource> source;  // used when tree is null
  double timeSec = 0.0;                  // tree time to evaluate at
  int coarseResolution = 48;             // first answer (skipped when >= fineResolution)
  int fineResolution = 128;              // refined answer once the request stays unchanged
  int threads = 0;                       // polygoniser threads for this request (0: the worker's own)
};

struct PreviewResult {
  uint64_t requestId = 0;  // submit()'s id of the request this answers
  uint64_t serial = 0;     // increases with every published result
  double timeSec = 0.0;
  int resolution = 0;
  bool final = false;      // the fine answer (no better one will come for this request)
  TriangleMesh mesh;       // in the tree's space; empty on error or for an empty shape
  PolygonizeStats stats;
  std::string error;       // invalid tree or polygoniser error; empty on success
};

struct PreviewCounters {
  uint64_t runsStarted = 0;    // polygoniser runs begun (one per level)
  uint64_t runsCancelled = 0;  // runs stopped by a newer request
  uint64_t published = 0;      // results published
};

// Worker threads for a preview drawn interactively: every hardware thread but
// one, which stays with the thread that draws the frames (at least 1). On a
// 2-core machine with lavapipe, bench scrub at 96^3 measured frame p95 33-38 ms
// with one worker thread against 36-49 ms with two, and no slower previews.
int interactivePreviewThreads();
// Worker threads while the frame loop is paced (scrubbing, scene/scrub_pacing.h): every hardware
// thread, the loop drawing only on a new mesh or once a paced interval.
int pacedPreviewThreads();

class PreviewPolygonizer {
 public:
  // threads: polygoniser threads per run (0: all hardware threads).
  explicit PreviewPolygonizer(int threads = 0);
  // Cancels the run in progress and joins the worker.
  ~PreviewPolygonizer();
  PreviewPolygonizer(const PreviewPolygonizer&) = delete;
  PreviewPolygonizer& operator=(const PreviewPolygonizer&) = delete;

  // Submits a request and returns its id. A request equal to the latest one
  // (same tree contents, time and resolutions) changes nothing and returns the
  // latest id; any other supersedes it: a refining (fine) run in progress is
  // cancelled, while a coarse run is finished and published first, so that
  // scrubbing a shape whose coarse polygonisation takes longer than a frame
  // still shows a new mesh every coarse run instead of none until it stops
  // (the worker then takes the newest request). Requests without a tree
  // or a source are ignored (id 0).
  uint64_t submit(PreviewRequest request);
  // The newest published result, or null before the first. Never blocks on the worker's runs.
  std::shared_ptr<const PreviewResult> latest() const;
  // Serial of latest() (0 before the first): cheap polling for "is there something new".
  uint64_t latestSerial() const { return serial_.load(); }
  // True while a request is waiting or running.
  bool busy() const;
  // Waits until the worker is idle (the latest request fully answered) or timeoutSec passes. Returns idle.
  bool waitIdle(double timeoutSec) const;
  PreviewCounters counters() const;
  // Called on a worker thread after every published result, by every PreviewPolygonizer (the
  // editor wakes its frame loop with it: glfwPostEmptyEvent). Set it before the first is made.
  static void setPublishHook(void (*hook)());
  // Results published so far by every PreviewPolygonizer (the paced frame loop draws when it changes).
  static uint64_t publishedTotal();
  // Waits until publishedTotal() differs from seen or timeoutSec passes (a loop without window
  // events to wake it: the bench). Returns whether it differs.
  static bool waitForPublish(uint64_t seen, double timeoutSec);

 private:
  void run();
  void publish(std::shared_ptr<PreviewResult> r);

  const int threads_;
  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;  // worker: a request or stop
  mutable std::condition_variable idle_;  // waitIdle
  PreviewRequest pending_;                // latest request
  uint64_t pendingId_ = 0;                // id of pending_ (0: none yet)
  uint64_t doneId_ = 0;                   // last request fully handled
  bool running_ = false;
  int runningLevel_ = -1;                 // level of the run in progress (0 coarse, 1 fine; -1 none)
  bool stop_ = false;
  std::atomic<bool> cancel_{false};
  std::atomic<uint64_t> serial_{0};
  PolygonizeHistory history_[2];          // the worker's, per level (coarse, fine): temporal coherence
  std::shared_ptr<const PreviewResult> latest_;
  PreviewCounters counters_;
  std::thread worker_;
};

}  // namespace animorph
