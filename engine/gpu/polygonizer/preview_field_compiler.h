#pragma once
// The GPU preview's field compiles (PreviewSource::field: a BlobTree flattened
// into one FieldProgram; for the animorphosis demo's C(t), 7,300 nodes, 58 ms
// on an H100's host) on a thread of their own, so that the frame loop never
// waits for one (implicit_preview.h). The latest request wins, as in the CPU
// preview worker (poly/preview_polygonizer.h): a newer request replaces the one
// waiting; the one being compiled is finished and published (it is a newer
// shape than the one on screen). The UI thread polls latest(); only a
// screenshot waits (waitFor). The same compile runs on the calling thread with
// compileHere() (fields that take a fraction of a millisecond).
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/poly/preview_polygonizer.h"

namespace animorph::gpu {

class GpuPreparedFrame;
struct GpuField;
struct GpuPolygonizeSettings;

// The GPU polygoniser's settings for the preview of field at resolution (the record's and the
// prepared frame's, which must agree for the record to use it).
GpuPolygonizeSettings previewGpuSettings(const PreviewField& field, int resolution);
// What the GPU polygonises for the preview of field: its program, with its colour program (a
// morph's stand-ins split into their colour samples) for the colour pass where it has one. The
// record's and the prepared frame's (they must agree); valid while field lives.
GpuField previewGpuField(const PreviewField& field);

// One compiled request: the field, or why the GPU cannot polygonise the shape.
struct CompiledPreviewField {
  uint64_t id = 0;  // the request's (ids increase with every request, here or on the thread)
  std::shared_ptr<const PreviewSource> source;
  int resolution = 0;
  double timeSec = 0.0;             // scene time of the shape (what the status line shows once drawn)
  std::optional<PreviewField> field;  // set on success
  // With field: the GPU frame's host half (grid bounds, packed programs, region lists) for
  // previewGpuSettings(*field, resolution), made with the compile (GpuPolygonizer::prepare), so that
  // the recording thread only uploads and records; with the change bounds from the field compiled
  // before it (temporal coherence: used when that one was the last recorded). Null when it failed (the record prepares on the
  // spot and reports the error).
  std::shared_ptr<const GpuPreparedFrame> prepared;
  // With field: the grid it is polygonised on (GpuPolygonizeSettings::grid; the record's settings are
  // previewGpuSettings(*field, resolution) with it): the grid of the field compiled before it while
  // this shape fits in that one (holdScrubbingGrid, as the CPU worker scrubs), else its own.
  std::optional<PolygonizeGrid> grid;
  double prepareMs = 0.0;  // its host time (not part of milliseconds)
  // field() failed, or the GPU cannot express the program (GpuPolygonizer::unsupported); empty on success.
  std::string error;
  double milliseconds = 0.0;  // wall time of field() and the check (the preparation apart)
  bool onCompileThread = false;
  bool matches(const PreviewSource& s, int res) const;
};

struct PreviewFieldCounters {
  uint64_t onCompileThread = 0;  // compiles the thread ran
  uint64_t onCallerThread = 0;   // compileHere() calls
  double compileThreadMs = 0.0;  // their total wall time
  double callerThreadMs = 0.0;
  uint64_t superseded = 0;  // requests replaced while waiting (never compiled)
  double prepareMs = 0.0;   // the GPU frames prepared with them (CompiledPreviewField::prepareMs), in all
  // How the compiled programs were made (PreviewField::refill): the structure kept, only values
  // computed (a scrub of C(t)); built because nothing was kept (the first of a C, or after an edit)
  // or because the structure changed; by a source that does not refill (BlobTrees), or failed.
  uint64_t refilled = 0, firstCompiles = 0, structureChanged = 0, notRefilled = 0;
};

// Same shape (pointer first: sameAs may compare whole trees).
bool samePreviewShape(const PreviewSource& a, const PreviewSource& b);

class PreviewFieldCompiler {
 public:
  // deviceLoopLimit: the recording device's (GpuPolygonizer::loopLimit), which the frames are
  // prepared for; a frame prepared for another limit is prepared again by the record.
  explicit PreviewFieldCompiler(uint64_t deviceLoopLimit = 0);
  ~PreviewFieldCompiler();  // the compile in progress finishes first (field() cannot be cancelled)
  PreviewFieldCompiler(const PreviewFieldCompiler&) = delete;
  PreviewFieldCompiler& operator=(const PreviewFieldCompiler&) = delete;

  // Asks for source's field at resolution and returns the request's id. The same shape and
  // resolution as the request waiting or being compiled returns that request's id (nothing more to
  // do); any other replaces the waiting one. Never blocks on a compile.
  uint64_t request(std::shared_ptr<const PreviewSource> source, int resolution, double timeSec);
  // Drops the request waiting, if any (the shape it asked for is no longer wanted).
  void dropWaiting();
  // The newest compiled request, or null before the first. Never blocks on a compile.
  std::shared_ptr<const CompiledPreviewField> latest() const;
  // Compiles on the calling thread, with a new id (newer than every request so far).
  std::shared_ptr<const CompiledPreviewField> compileHere(std::shared_ptr<const PreviewSource> source,
                                                          int resolution, double timeSec);
  // Waits until request id (or a newer one) is published, at most timeoutSec. Returns whether it is.
  bool waitFor(uint64_t id, double timeoutSec) const;
  // True while a request waits or is being compiled.
  bool busy() const;
  // Waits until nothing waits or is compiled, at most timeoutSec. Returns idle.
  bool waitIdle(double timeoutSec) const;
  PreviewFieldCounters counters() const;
  // The recording polygoniser's GpuPolygonizer::conservativeRegions(), for the frames prepared next.
  void setConservativeRegions(bool on) { conservative_ = on; }

 private:
  struct Request {
    uint64_t id = 0;
    std::shared_ptr<const PreviewSource> source;
    int resolution = 0;
    double timeSec = 0.0;
  };
  // previous: the newest field compiled before (its prepared frame gives the change bounds for the
  // GPU's temporal coherence); may be null.
  static std::shared_ptr<const CompiledPreviewField> compile(const Request& r, bool onCompileThread, uint64_t loopLimit,
                                                             const std::shared_ptr<const CompiledPreviewField>& previous,
                                                             bool conservative);
  void run();

  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;  // the thread: a request or stop
  mutable std::condition_variable done_;  // waitFor, waitIdle
  uint64_t nextId_ = 0;
  std::optional<Request> waiting_;
  std::optional<Request> running_;
  std::shared_ptr<const CompiledPreviewField> latest_;
  std::shared_ptr<const CompiledPreviewField> latestAny_;  // the newest compiled here or on the thread
  PreviewFieldCounters counters_;
  bool stop_ = false;
  const uint64_t loopLimit_;
  std::atomic<bool> conservative_{false};
  std::thread thread_;
};

}  // namespace animorph::gpu
