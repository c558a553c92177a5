#include "gpu/polygonizer/implicit_preview.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <cstdio>

#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/polygonizer/preview_field_compiler.h"
#include "gpu/vulkan/command_resources.h"
#include "gpu/vulkan/vk_check.h"

namespace animorph::gpu {

namespace {
double nowSec() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

PreviewBackend choosePreviewBackend(PreviewDevice preference, VkPhysicalDeviceType deviceType, PreviewWork work) {
  if (preference == PreviewDevice::Gpu) return {true, "GPU (preference)"};
  if (preference == PreviewDevice::Cpu) return {false, "CPU (preference)"};
  switch (deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      if (work == PreviewWork::ConvolutionMorph)
        return {true, "GPU (auto: convolution stand-ins, faster than the worker even on this CPU device)"};
      return {false, "CPU (auto: the Vulkan device is a CPU, the worker is faster for this scene)"};
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return {true, "GPU (auto: discrete GPU)"};
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return {true, "GPU (auto: integrated GPU)"};
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return {true, "GPU (auto: virtual GPU)"};
    default: return {false, "CPU (auto: unknown device type)"};
  }
}

std::string describePreviewStatus(const ImplicitPreviewStatus& st, const PreviewBackend& backend) {
  std::string s;
  char buf[160];
  if (!st.error.empty()) {
    s = "preview error: " + st.error;
  } else if (st.compiling && st.hasMesh && st.resolution > 0) {  // the CPU worker fills in
    std::snprintf(buf, sizeof buf, "preview %d^3 CPU %.0f ms, %zu tris (GPU shaders compiling)", st.resolution,
                  st.milliseconds, st.triangles);
    s = buf;
  } else if (st.compiling) {
    s = "preview: compiling GPU shaders";
  } else if (!st.hasMesh || st.resolution == 0) {  // (GPU: the first record's figures are not read back yet)
    s = "preview: computing";
  } else {
    std::snprintf(buf, sizeof buf, "preview %d^3 %s %.0f ms, %zu tris%s", st.resolution, st.gpu ? "GPU" : "CPU",
                  st.milliseconds, st.triangles, st.refining ? " (refining)" : "");
    s = buf;
  }
  if (!st.gpuFallback.empty()) s += " | " + st.gpuFallback + ": using the CPU";
  else s += " | " + backend.why;
  return s;
}

ImplicitPreview::ImplicitPreview(Context& ctx) : ctx_(ctx) {}

ImplicitPreview::~ImplicitPreview() {
  worker_.reset();  // cancels and joins
  compiler_.reset();  // joins (after the compile in progress)
  VkDevice dev = ctx_.device();
  for (uint32_t i = 0; i < kFramesInFlight; ++i)
    if (fences_[i]) {
      if (pending_[i]) vkWaitForFences(dev, 1, &fences_[i], VK_TRUE, UINT64_MAX);
      vkDestroyFence(dev, fences_[i], nullptr);
    }
  if (pool_) vkDestroyCommandPool(dev, pool_, nullptr);
  poly_.reset();
  retired_.clear();
  mesh_.reset();
}

void ImplicitPreview::update(std::shared_ptr<const PreviewSource> source, double timeSec,
                             const ImplicitPreviewSettings& s) {
  if (!source) return;
  if (s.gpu && gpuFailure_.empty() && updateGpu(source, timeSec, s)) {
    gpuActive_ = true;
    if (compiling_) {
      // The shape's pipelines are compiling (~1 s on lavapipe): the CPU worker draws it meanwhile,
      // so the viewport shows this shape rather than the last one or nothing.
      if (!cpuFillIn_) {
        if (mesh_) retired_.emplace_back(frame_, std::move(mesh_));
        result_.reset();
        uploadedSerial_ = 0;  // the worker's newest mesh, even one it made before, is this shape's or newer
        cpuFillIn_ = true;
      }
      updateCpu(std::move(source), timeSec, s);
    } else if (cpuFillIn_) {
      endCpuFillIn();
    }
    return;
  }
  gpuActive_ = false;
  cpuFillIn_ = false;  // the worker's mesh is the CPU path's now
  // Back on the GPU later, the shape starts over, and until its first record the CPU's mesh stays
  // on screen (draw()), not the GPU's mesh of a shape from before.
  gpuSource_.reset();
  lastAsked_.reset();
  recordedField_.reset();
  ready_.reset();
  fieldPending_ = false;
  gpuDrawable_ = false;
  updateCpu(std::move(source), timeSec, s);
}

void ImplicitPreview::endCpuFillIn() {
  cpuFillIn_ = false;
  worker_.reset();  // cancels its run: the GPU path has the cores
  if (mesh_) retired_.emplace_back(frame_, std::move(mesh_));
  result_.reset();
}

void ImplicitPreview::updateCpu(std::shared_ptr<const PreviewSource> source, double timeSec,
                                const ImplicitPreviewSettings& s) {
  if (!worker_) {  // one worker per preview: each request says its threads (its history stays)
    worker_ = std::make_unique<PreviewPolygonizer>(s.threads);
    uploadedSerial_ = 0;
  }
  PreviewRequest r;
  r.source = std::move(source);
  r.timeSec = timeSec;
  r.coarseResolution = s.interactiveResolution;
  r.fineResolution = s.refinedResolution;
  r.threads = s.threads > 0 ? s.threads : pacedPreviewThreads();  // 0: all, as the worker's own
  worker_->submit(std::move(r));
  uploadNew();
}

void ImplicitPreview::uploadNew() {
  if (!worker_ || worker_->latestSerial() == uploadedSerial_) return;
  auto r = worker_->latest();
  if (!r) return;
  uploadedSerial_ = r->serial;
  result_ = r;
  if (mesh_) retired_.emplace_back(frame_, std::move(mesh_));
  uploadError_.clear();
  if (!r->error.empty() || r->mesh.positions.empty()) return;  // nothing inside: draw nothing
  Mesh m;
  m.name = "implicit preview";
  m.positions = r->mesh.positions;
  m.normals = r->mesh.normals;
  m.indices = r->mesh.indices;
  if (r->mesh.colors.size() == r->mesh.positions.size()) m.colors = r->mesh.colors;  // drawn in them (draw())
  auto up = GpuMesh::upload(ctx_, m);
  if (up) mesh_ = std::move(*up);
  else uploadError_ = up.error();
}

uint64_t ImplicitPreview::gpuPreparesInRecord() const { return poly_ ? poly_->preparesInRecord() : 0; }
uint64_t ImplicitPreview::gpuCutFramesRedone() const { return poly_ ? poly_->cutFramesRedone() : 0; }

void ImplicitPreview::prewarm(const PreviewSource& source, const ImplicitPreviewSettings& s) {
  if (!s.gpu || !gpuFailure_.empty()) return;
  if (!poly_) {
    if (Status st = initGpu(); !st) {
      gpuFailure_ = "GPU preview unavailable: " + st.error();
      return;
    }
  }
  const double t0 = nowSec();
  auto field = source.field(s.interactiveResolution);
  lastFieldMs_ = 1000.0 * (nowSec() - t0);  // (whether the next fields compile on this thread)
  if (!field) return;  // update() reports it
  GpuPolygonizeSettings gs;
  gs.resolution = s.interactiveResolution;
  gs.bounds = field->bounds;
  gs.noiseAmplitude = field->noiseAmplitude;
  gs.noiseFrequency = field->noiseFrequency;
  poly_->prewarm(GpuField::single(field->fieldProgram()), gs);
}

Status ImplicitPreview::initGpu() {
  auto p = GpuPolygonizer::create(ctx_);
  if (!p) return Error{p.error()};
  VkDevice dev = ctx_.device();
  if (Status c = createCommandResources(dev, ctx_.queueFamily(), kFramesInFlight, &pool_, cmds_, fences_); !c) return c;
  poly_ = std::move(*p);
  return {};
}

void ImplicitPreview::pollGpu() {
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    if (!pending_[i]) continue;
    VkResult r = vkGetFenceStatus(ctx_.device(), fences_[i]);
    if (r == VK_NOT_READY) continue;
    pending_[i] = false;
    if (r != VK_SUCCESS) {
      gpuFailure_ = "GPU preview: " + std::string(vkResultName(r));
      continue;
    }
    gpuShownMs_ = 1000.0 * (nowSec() - submittedAt_[i]);
    gpuShownRes_ = submittedRes_[i];
  }
}

std::shared_ptr<const CompiledPreviewField> ImplicitPreview::takeField(
    const std::shared_ptr<const PreviewSource>& source, int res, double timeSec, bool settle) {
  if (!compiler_) compiler_ = std::make_unique<PreviewFieldCompiler>(GpuPolygonizer::loopLimit(ctx_.properties()));
  auto keep = [&](std::shared_ptr<const CompiledPreviewField> c) {
    lastFieldMs_ = c->milliseconds;
    ready_ = std::move(c);
  };
  // The newest field the thread has compiled, this shape's or an older one's: newer than the mesh on screen.
  auto pollThread = [&] {
    auto latest = compiler_->latest();
    if (latest && latest->id > takenFieldId_ && (!ready_ || latest->id > ready_->id)) keep(std::move(latest));
  };
  pollThread();
  if (ready_ && ready_->matches(*source, res)) return ready_;
  // A screenshot must show this shape, and a field measured cheap costs less here than a frame's
  // delay: compiled on this thread (a request waiting is for an older shape).
  if (settle || (lastFieldMs_ >= 0.0 && lastFieldMs_ < kCompileHereMs)) {
    compiler_->dropWaiting();
    keep(compiler_->compileHere(source, res, timeSec));
    return ready_;
  }
  const bool threadIdle = !compiler_->busy();
  const uint64_t id = compiler_->request(source, res, timeSec);
  // The first field of this preview (its cost unknown; most take well under a millisecond): wait a
  // moment for it, so that a cheap shape is recorded in its own frame as before.
  if (lastFieldMs_ < 0.0 && threadIdle && compiler_->waitFor(id, kFirstFieldWaitSec)) pollThread();
  return ready_;
}

void ImplicitPreview::fieldTaken(const std::shared_ptr<const CompiledPreviewField>& field) {
  takenFieldId_ = std::max(takenFieldId_, field->id);
  if (ready_ == field) ready_.reset();
}

ImplicitPreview::GpuAsk ImplicitPreview::askGpu(const std::shared_ptr<const PreviewSource>& source,
                                                const ImplicitPreviewSettings& s) {
  GpuAsk ask;
  // The frame before asked for this shape too (it was recorded, or it waited: pacing, pipelines, its field).
  // (sameAs may walk whole trees: C(t) snapshots all have tree time 0, so two are compared node by
  // node up to the first difference)
  ask.repeated = lastAsked_ && samePreviewShape(*lastAsked_, *source);
  ask.sameShape = gpuSource_ && (gpuSource_ == lastAsked_ ? ask.repeated : samePreviewShape(*gpuSource_, *source));
  lastAsked_ = source;
  const double now = nowSec();
  ask.frameSec = now - lastUpdateAt_;
  if (!ask.repeated) {
    previousShapeLasted_ = now - shapeSince_;
    shapeSince_ = now;
  }
  // On a CPU device, while the user drags (the shape before this one lasted a moment), a shape
  // that repeats is refined only once it has held still for kRefineDelaySec: a mouse that pauses
  // for a frame or two would otherwise start a refined polygonisation the next frames wait for
  // (the frame shares the CPU and the queue with it; dragging the morph's noise frequency: 22-28
  // fps without the hold, 24-32 with it). A shape that lasted (a step, a project opened) is
  // refined at once, and on a GPU always (a refined record takes a few milliseconds there).
  refineHeld_ = ctx_.deviceType() == VK_PHYSICAL_DEVICE_TYPE_CPU && ask.repeated && !s.settle &&
                previousShapeLasted_ < kInteractionSec && now - shapeSince_ < kRefineDelaySec;
  ask.res = (ask.repeated || s.settle) && !refineHeld_ ? s.refinedResolution : s.interactiveResolution;
  lastUpdateAt_ = now;
  ask.recordedLast = lastUpdateRecorded_;
  lastUpdateRecorded_ = false;
  deferred_ = false;
  fieldPending_ = false;
  return ask;
}

std::optional<bool> ImplicitPreview::lastRecordSettles() {
  const uint64_t last = serial_ - 1;
  const uint32_t lastSlot = uint32_t(last % kFramesInFlight);
  if (pending_[lastSlot]) {
    const VkResult r = vkGetFenceStatus(ctx_.device(), fences_[lastSlot]);
    if (r == VK_NOT_READY) return true;  // busy() (pending) asks for the frames that look again
    pollGpu();
    if (!gpuFailure_.empty()) return false;
  }
  Result<bool> fitted = poly_->recordFitted(last);
  if (fitted && *fitted) {
    settled_ = true;
    return true;
  }
  // It overflowed (the buffers grew) or its counters are gone: record the shape again.
  return std::nullopt;
}

std::optional<bool> ImplicitPreview::unusableField(const std::shared_ptr<const CompiledPreviewField>& field,
                                                   const std::shared_ptr<const PreviewSource>& source) {
  if (!field) {
    fieldPending_ = true;
    return true;
  }
  if (field->error.empty()) return std::nullopt;
  fieldTaken(field);
  if (samePreviewShape(*field->source, *source)) {
    fieldFallback_ = field->error;
    fieldFailed_ = source;
    return false;
  }
  fieldPending_ = true;  // an older shape's: this one is on its way
  return true;
}

bool ImplicitPreview::polygonizeNow(const GpuField& gf, const GpuPolygonizeSettings& gs,
                                    const std::shared_ptr<const CompiledPreviewField>& field,
                                    const std::shared_ptr<const PreviewSource>& source, int res, double timeSec) {
  VkDevice dev = ctx_.device();
  for (uint32_t i = 0; i < kFramesInFlight; ++i)
    if (pending_[i] && vkWaitForFences(dev, 1, &fences_[i], VK_TRUE, UINT64_MAX) != VK_SUCCESS) {
      gpuFailure_ = "GPU preview: waiting for the GPU failed";
      return false;
    }
  pollGpu();
  Result<GpuPolygonizeStats> done = poly_->polygonize(gf, gs, field->prepared.get());
  if (!done) {
    gpuFailure_ = "GPU preview: " + done.error();
    return false;
  }
  gpuShownMs_ = done->milliseconds;
  gpuShownRes_ = res;
  gpuDrawnTime_ = timeSec;
  gpuSource_ = source;
  gpuResolution_ = res;
  recordedField_ = field;
  fieldTaken(field);
  settled_ = true;
  gpuDrawable_ = true;
  return true;
}

bool ImplicitPreview::submitRecord(const GpuField& gf, const GpuPolygonizeSettings& gs,
                                   const std::shared_ptr<const CompiledPreviewField>& field,
                                   const std::shared_ptr<const PreviewSource>& source, int res) {
  const bool sameRecord = gpuSource_ && gpuResolution_ == field->resolution && samePreviewShape(*gpuSource_, *field->source);
  VkDevice dev = ctx_.device();
  const uint32_t slot = uint32_t(serial_ % kFramesInFlight);
  // The record kFramesInFlight ago used this slot; GpuPolygonizer::record reads its counters. While
  // the GPU is still on it this frame draws the last mesh and the next one records (the field
  // stays ready): the UI thread does not wait for the GPU.
  if (pending_[slot]) {
    const VkResult w = vkGetFenceStatus(dev, fences_[slot]);
    if (w == VK_NOT_READY) {
      deferred_ = true;
      return true;
    }
    if (w != VK_SUCCESS) {
      gpuFailure_ = "GPU preview: " + std::string(vkResultName(w));
      return false;
    }
    pollGpu();
  }
  if (!sameRecord) {
    recordsOfShape_ = 0;
    settled_ = false;
  }
  VkCommandBuffer cmd = cmds_[slot];
  vkResetCommandBuffer(cmd, 0);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &bi);
  Status st = poly_->record(cmd, serial_, gf, gs, field->prepared.get());
  if (compiler_) compiler_->setConservativeRegions(poly_->conservativeRegions());
  vkEndCommandBuffer(cmd);
  if (!st) {
    gpuFailure_ = "GPU preview: " + st.error();
    return false;
  }
  vkResetFences(dev, 1, &fences_[slot]);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  if (VkResult r = vkQueueSubmit(ctx_.queue(), 1, &si, fences_[slot]); r != VK_SUCCESS) {
    gpuFailure_ = "GPU preview: vkQueueSubmit: " + std::string(vkResultName(r));
    return false;
  }
  pending_[slot] = true;
  submittedAt_[slot] = nowSec();
  submittedRes_[slot] = field->resolution;
  gpuDrawnTime_ = field->timeSec;
  lastUpdateRecorded_ = true;
  ++serial_;
  ++recordsOfShape_;
  // Normally the next frame settles it (lastRecordSettles). Records that overflowed again are
  // also read kFramesInFlight records later inside record(): once those of a record of this shape
  // show it fitted, the records since fit too.
  settled_ = recordsOfShape_ > int(kFramesInFlight) && !poly_->lastStats().overflowed;
  gpuSource_ = field->source;
  gpuResolution_ = field->resolution;
  recordedField_ = field;
  fieldTaken(field);
  // An older shape's field (compiled while this one was asked for): this one is still on its way.
  fieldPending_ = !field->matches(*source, res);
  gpuDrawable_ = true;
  return true;
}

bool ImplicitPreview::updateGpu(const std::shared_ptr<const PreviewSource>& source, double timeSec,
                                const ImplicitPreviewSettings& s) {
  if (!poly_) {
    if (Status st = initGpu(); !st) {
      gpuFailure_ = "GPU preview unavailable: " + st.error();
      return false;
    }
  }
  pollGpu();
  if (!gpuFailure_.empty()) return false;
  // A shape whose field failed or that the GPU cannot express: the CPU worker draws it (fieldFallback_ says why).
  if (fieldFailed_ && samePreviewShape(*fieldFailed_, *source)) return false;
  fieldFailed_.reset();
  fieldFallback_.clear();
  const GpuAsk ask = askGpu(source, s);
  const int res = ask.res;
  if (ask.sameShape && res == gpuResolution_ && settled_) {  // quiet; a field compiled for another shape is not wanted
    ready_.reset();
    if (compiler_) compiler_->dropWaiting();
    return true;
  }
  // Frame pacing: after a frame over the 30 fps budget that recorded a new shape, this frame
  // draws the last mesh and the new shape waits (its field compiles meanwhile off this thread;
  // the next frame asks for it again and records it).
  constexpr double kFrameBudgetSec = 1.0 / 30.0;
  if (s.paceGpu && !ask.repeated && !s.settle && gpuDrawable_ && ask.recordedLast && ask.frameSec > kFrameBudgetSec) {
    deferred_ = true;
    if (compiler_ && !(lastFieldMs_ >= 0.0 && lastFieldMs_ < kCompileHereMs)) compiler_->request(source, res, timeSec);
    return true;
  }
  // The shape just recorded, again: that record drew it. Once it has completed, its counters say
  // whether it fitted (then the preview goes quiet); until then nothing new is recorded.
  if (ask.sameShape && res == gpuResolution_ && recordsOfShape_ > 0 && !s.settle)
    if (std::optional<bool> decided = lastRecordSettles()) return *decided;
  std::shared_ptr<const CompiledPreviewField> field;
  if (ask.sameShape && res == gpuResolution_ && recordedField_) field = recordedField_;
  // The field of this shape, or of the newest shape compiled since the last record: compiled off
  // this thread (PreviewFieldCompiler) unless it is cheap or a screenshot needs it now. While it
  // compiles the viewport keeps the last mesh.
  if (!field) field = takeField(source, res, timeSec, s.settle);
  if (std::optional<bool> decided = unusableField(field, source)) return *decided;
  const GpuField gf = previewGpuField(*field->field);  // the colour pass walks its colour program
  GpuPolygonizeSettings gs = previewGpuSettings(*field->field, field->resolution);
  gs.grid = field->grid;  // the grid its prepared frame was made on (held while scrubbing)
  // A kind of shape whose pipelines are not compiled yet: compile them in the background while the
  // CPU worker draws it (update(); the frame would otherwise stall ~1 s on lavapipe); retried every frame.
  // A screenshot (settle) waits for them instead: it must show this shape.
  compiling_ = !s.settle && !poly_->ready(gf, gs);
  if (compiling_) {
    poly_->prewarm(gf, gs);
    deferred_ = true;
    return true;
  }
  // A screenshot: the whole shape in this frame. A record reads its counters frames later, so the
  // first record of a shape that outgrows the buffers would draw nothing; the synchronous
  // polygonisation grows them and redoes it until the mesh fits (after this preview's own
  // records, which use the same buffers).
  if (s.settle) return polygonizeNow(gf, gs, field, source, res, timeSec);
  return submitRecord(gf, gs, field, source, res);
}

void ImplicitPreview::draw(Scene& scene, const glm::mat4& model, const glm::vec4& color, bool selected) const {
  // (the GPU path's first shape after the CPU's: the CPU's mesh until the GPU's is recorded)
  if (usingGpu() && !(cpuFillIn_ && mesh_) && (gpuDrawable_ || !mesh_)) {
    if (!gpuDrawable_) return;
    GeneratedMeshDraw g = poly_->generatedMesh(color);
    g.model = model;
    g.selected = selected;
    scene.generatedMeshes.push_back(g);
    return;
  }
  if (!mesh_) return;
  MeshDraw md;
  md.mesh = mesh_.get();
  md.model = model;
  md.color = color;
  md.doubleSided = true;  // a surface cut by the grid bounds shows its inside
  md.selected = selected;
  scene.meshes.push_back(md);
}

ImplicitPreviewStatus ImplicitPreview::status() const {
  ImplicitPreviewStatus st;
  st.gpuFallback = !gpuFailure_.empty() ? gpuFailure_ : fieldFallback_;
  if (usingGpu() && !(cpuFillIn_ && result_)) {
    st.gpu = true;
    st.hasMesh = gpuDrawable_;
    st.resolution = gpuShownRes_;
    st.milliseconds = gpuShownMs_;
    st.timeSec = gpuDrawnTime_;
    st.triangles = poly_ ? poly_->lastStats().triangles : 0;
    st.refining = busy();
    st.compiling = compiling_;
    return st;
  }
  st.refining = busy();
  st.compiling = cpuFillIn_ && compiling_;
  if (!uploadError_.empty()) st.error = uploadError_;
  if (!result_) return st;
  if (!result_->error.empty()) st.error = result_->error;
  st.hasMesh = true;
  st.resolution = result_->resolution;
  st.milliseconds = result_->stats.milliseconds;
  st.timeSec = result_->timeSec;
  st.triangles = result_->mesh.triangleCount();
  return st;
}

bool ImplicitPreview::busy() const {
  if (usingGpu()) {
    for (bool p : pending_)
      if (p) return true;
    return deferred_ || refineHeld_ || fieldPending_ || !settled_;
  }
  // A finished result not uploaded yet (the next update() does) still counts.
  return worker_ && (worker_->busy() || worker_->latestSerial() != uploadedSerial_);
}

bool ImplicitPreview::needsFrames() const {
  if (usingGpu()) return busy();
  return worker_ && worker_->latestSerial() != uploadedSerial_;
}

bool ImplicitPreview::waitIdle(double timeoutSec) {
  if (usingGpu()) {
    const uint64_t ns = uint64_t(std::max(0.0, timeoutSec) * 1e9);
    if (cpuFillIn_ && worker_) {  // the worker's mesh of the shape first, then the compiler
      worker_->waitIdle(timeoutSec);
      uploadNew();
    }
    // The field being compiled, then the pipelines: the next update records the shape.
    bool idle = !fieldPending_ || !compiler_ || compiler_->waitIdle(timeoutSec);
    idle = (!compiling_ || poly_->waitForCompilation(timeoutSec)) && idle;
    if (refineHeld_) {  // the next update after the hold records the refined shape
      const double left = std::min(timeoutSec, shapeSince_ + kRefineDelaySec - nowSec());
      if (left > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
    }
    for (uint32_t i = 0; i < kFramesInFlight; ++i)
      if (pending_[i] && vkWaitForFences(ctx_.device(), 1, &fences_[i], VK_TRUE, ns) != VK_SUCCESS) idle = false;
    pollGpu();
    return idle;
  }
  bool idle = !worker_ || worker_->waitIdle(timeoutSec);
  uploadNew();
  return idle;
}

void ImplicitPreview::endFrame() {
  ++frame_;
  std::erase_if(retired_, [&](const auto& r) { return frame_ - r.first > kFramesInFlight + 1; });
}

}  // namespace animorph::gpu
