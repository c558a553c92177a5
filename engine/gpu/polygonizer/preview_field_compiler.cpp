#include "gpu/polygonizer/preview_field_compiler.h"

#include <chrono>

#include "core/poly/scrubbing_grid.h"
#include "gpu/polygonizer/gpu_polygonizer.h"

namespace animorph::gpu {

namespace {
using Clock = std::chrono::steady_clock;
}

bool samePreviewShape(const PreviewSource& a, const PreviewSource& b) { return &a == &b || a.sameAs(b); }

bool CompiledPreviewField::matches(const PreviewSource& s, int res) const {
  return source && resolution == res && samePreviewShape(*source, s);
}

GpuPolygonizeSettings previewGpuSettings(const PreviewField& field, int resolution) {
  GpuPolygonizeSettings gs;
  gs.resolution = resolution;
  gs.bounds = field.bounds;
  gs.noiseAmplitude = field.noiseAmplitude;
  gs.noiseFrequency = field.noiseFrequency;
  return gs;
}

GpuField previewGpuField(const PreviewField& field) {
  GpuField gf = GpuField::single(field.fieldProgram());
  gf.colors = field.colorProgram.get();
  return gf;
}

PreviewFieldCompiler::PreviewFieldCompiler(uint64_t deviceLoopLimit)
    : loopLimit_(deviceLoopLimit), thread_([this] { run(); }) {}

PreviewFieldCompiler::~PreviewFieldCompiler() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

uint64_t PreviewFieldCompiler::request(std::shared_ptr<const PreviewSource> source, int resolution, double timeSec) {
  if (!source) return 0;
  uint64_t id = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto same = [&](const std::shared_ptr<const PreviewSource>& s, int res) {
      return s && res == resolution && samePreviewShape(*s, *source);
    };
    if (waiting_ && same(waiting_->source, waiting_->resolution)) return waiting_->id;
    if (running_ && same(running_->source, running_->resolution)) return running_->id;
    if (waiting_) ++counters_.superseded;
    waiting_ = Request{++nextId_, std::move(source), resolution, timeSec};
    id = nextId_;
  }
  wake_.notify_all();
  return id;
}

void PreviewFieldCompiler::dropWaiting() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!waiting_) return;
  waiting_.reset();
  ++counters_.superseded;
  if (!running_) done_.notify_all();
}

std::shared_ptr<const CompiledPreviewField> PreviewFieldCompiler::latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_;
}

std::shared_ptr<const CompiledPreviewField> PreviewFieldCompiler::compile(
    const Request& r, bool onCompileThread, uint64_t loopLimit, const std::shared_ptr<const CompiledPreviewField>& previous,
    bool conservative) {
  const auto t0 = Clock::now();
  auto c = std::make_shared<CompiledPreviewField>();
  c->onCompileThread = onCompileThread;
  c->id = r.id;
  c->source = r.source;
  c->resolution = r.resolution;
  c->timeSec = r.timeSec;
  Result<PreviewField> field = r.source->field(r.resolution);
  if (!field) {
    c->error = field.error();
  } else if (std::string why = GpuPolygonizer::unsupported(GpuField::single(field->fieldProgram())); !why.empty()) {
    c->error = std::move(why);
  } else {
    c->field = std::move(*field);
    // The GPU frame's host half here too, off the recording thread (a failure is the record's to report).
    const auto p0 = Clock::now();
    const bool chained = previous && previous->field && previous->resolution == r.resolution;
    const GpuPreparedFrame* before = chained ? previous->prepared.get() : nullptr;
    const GpuField gf = previewGpuField(*c->field);
    GpuPolygonizeSettings gs = previewGpuSettings(*c->field, r.resolution);
    // Held from the field before while this one fits in it: a moving shape keeps its blocks too.
    if (Result<PolygonizeGrid> own = GpuPolygonizer::grid(gf, gs); own && !own->empty)
      c->grid = holdScrubbingGrid(*own, chained ? previous->grid : std::nullopt);
    gs.grid = c->grid;
    auto prepared = GpuPolygonizer::prepare(gf, gs, loopLimit, before, conservative);
    if (prepared) c->prepared = std::move(*prepared);
    c->prepareMs = std::chrono::duration<double, std::milli>(Clock::now() - p0).count();
  }
  // (the preparation apart: a record prepares on its own thread when given none, so only the
  // field's cost decides where the next field compiles, ImplicitPreview::takeField)
  c->milliseconds = std::chrono::duration<double, std::milli>(Clock::now() - t0).count() - c->prepareMs;
  return c;
}

namespace {

// One compiled field in the counters (the counts by how its program was made).
void countCompiled(const CompiledPreviewField& c, PreviewFieldCounters& n) {
  n.prepareMs += c.prepareMs;
  if (!c.field || !c.field->refill) ++n.notRefilled;
  else if (*c.field->refill == RefillOutcome::Refilled) ++n.refilled;
  else if (*c.field->refill == RefillOutcome::FirstCompile) ++n.firstCompiles;
  else ++n.structureChanged;
}

}  // namespace

std::shared_ptr<const CompiledPreviewField> PreviewFieldCompiler::compileHere(
    std::shared_ptr<const PreviewSource> source, int resolution, double timeSec) {
  Request r{0, std::move(source), resolution, timeSec};
  std::shared_ptr<const CompiledPreviewField> previous;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    r.id = ++nextId_;
    previous = latestAny_;
  }
  auto c = compile(r, false, loopLimit_, previous, conservative_.load());
  std::lock_guard<std::mutex> lock(mutex_);
  latestAny_ = c;
  ++counters_.onCallerThread;
  counters_.callerThreadMs += c->milliseconds;
  countCompiled(*c, counters_);
  return c;
}

bool PreviewFieldCompiler::waitFor(uint64_t id, double timeoutSec) const {
  std::unique_lock<std::mutex> lock(mutex_);
  auto published = [&] { return latest_ && latest_->id >= id; };
  // (a dropped request is never published: stop waiting once nothing is left to compile)
  done_.wait_for(lock, std::chrono::duration<double>(timeoutSec), [&] { return published() || (!waiting_ && !running_); });
  return published();
}

bool PreviewFieldCompiler::busy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return waiting_ || running_;
}

bool PreviewFieldCompiler::waitIdle(double timeoutSec) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return done_.wait_for(lock, std::chrono::duration<double>(timeoutSec), [&] { return !waiting_ && !running_; });
}

PreviewFieldCounters PreviewFieldCompiler::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

void PreviewFieldCompiler::run() {
  for (;;) {
    Request r;
    std::shared_ptr<const CompiledPreviewField> previous;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || waiting_; });
      if (stop_) return;
      r = std::move(*waiting_);
      waiting_.reset();
      running_ = r;
      previous = latestAny_;
    }
    std::shared_ptr<const CompiledPreviewField> c = compile(r, true, loopLimit_, previous, conservative_.load());
    {
      std::lock_guard<std::mutex> lock(mutex_);
      running_.reset();
      ++counters_.onCompileThread;
      counters_.compileThreadMs += c->milliseconds;
      countCompiled(*c, counters_);
      latestAny_ = c;
      latest_ = std::move(c);  // the thread's newest (a compileHere() since has a larger id: its caller keeps it)
    }
    done_.notify_all();
  }
}

}  // namespace animorph::gpu
