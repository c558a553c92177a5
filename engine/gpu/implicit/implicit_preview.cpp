#include "implicit/implicit_preview.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <cstdio>

#include "implicit/gpu_polygonizer.h"
#include "vulkan/command_resources.h"
#include "vulkan/vk_check.h"

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
  gpuSource_.reset();  // back on the GPU later, the shape starts over
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
  if (!worker_ || workerThreads_ != s.threads) {
    worker_ = std::make_unique<PreviewPolygonizer>(s.threads);
    workerThreads_ = s.threads;
    uploadedSerial_ = 0;
  }
  PreviewRequest r;
  r.source = std::move(source);
  r.timeSec = timeSec;
  r.coarseResolution = s.interactiveResolution;
  r.fineResolution = s.refinedResolution;
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
  auto up = GpuMesh::upload(ctx_, m);
  if (up) mesh_ = std::move(*up);
  else uploadError_ = up.error();
}

void ImplicitPreview::prewarm(const PreviewSource& source, const ImplicitPreviewSettings& s) {
  if (!s.gpu || !gpuFailure_.empty()) return;
  if (!poly_) {
    if (Status st = initGpu(); !st) {
      gpuFailure_ = "GPU preview unavailable: " + st.error();
      return;
    }
  }
  auto field = source.field(s.interactiveResolution);
  if (!field) return;  // update() reports it
  GpuPolygonizeSettings gs;
  gs.resolution = s.interactiveResolution;
  gs.bounds = field->bounds;
  gs.noiseAmplitude = field->noiseAmplitude;
  gs.noiseFrequency = field->noiseFrequency;
  poly_->prewarm(GpuField::single(field->program), gs);
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
  const bool sameShape = gpuSource_ && gpuSource_->sameAs(*source);
  // A shape asked for again after it waited a frame (pacing) has stopped changing too.
  const bool repeated = sameShape || (deferredSource_ && deferredSource_->sameAs(*source));
  deferredSource_.reset();
  const double now = nowSec(), frameSec = now - lastUpdateAt_;
  if (!repeated) {
    previousShapeLasted_ = now - shapeSince_;
    shapeSince_ = now;
  }
  // On a CPU device, while the user drags (the shape before this one lasted a moment), a shape
  // that repeats is refined only once it has held still for kRefineDelaySec: a mouse that pauses
  // for a frame or two would otherwise start a refined polygonisation the next frames wait for
  // (the frame shares the CPU and the queue with it; dragging the morph's noise frequency: 22-28
  // fps without the hold, 24-32 with it). A shape that lasted (a step, a project opened) is
  // refined at once, and on a GPU always (a refined record takes a few milliseconds there).
  refineHeld_ = ctx_.deviceType() == VK_PHYSICAL_DEVICE_TYPE_CPU && repeated && !s.settle && previousShapeLasted_ < kInteractionSec && now - shapeSince_ < kRefineDelaySec;
  const int res = (repeated || s.settle) && !refineHeld_ ? s.refinedResolution : s.interactiveResolution;
  lastUpdateAt_ = now;
  const bool recordedLast = lastUpdateRecorded_;
  lastUpdateRecorded_ = false;
  deferred_ = false;
  if (sameShape && res == gpuResolution_ && settled_) return true;  // quiet
  // Frame pacing: after a frame over the 30 fps budget that recorded a new shape, this frame
  // draws the last mesh and the new shape waits (gpuSource_ stays the old one, so the next
  // frame records it).
  constexpr double kFrameBudgetSec = 1.0 / 30.0;
  if (s.paceGpu && !repeated && !s.settle && gpuDrawable_ && recordedLast && frameSec > kFrameBudgetSec) {
    deferred_ = true;
    deferredSource_ = source;
    return true;
  }
  // The shape just recorded, again: that record drew it. Once it has completed, its counters say
  // whether it fitted (then the preview goes quiet); until then nothing new is recorded.
  if (sameShape && res == gpuResolution_ && recordsOfShape_ > 0 && !s.settle) {
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
  }
  if (!sameShape || res != gpuResolution_) {
    recordsOfShape_ = 0;
    settled_ = false;
  }

  auto field = source->field(res);
  if (!field) {
    fieldFallback_ = field.error();
    return false;
  }
  const GpuField gf = GpuField::single(field->program);
  if (std::string why = GpuPolygonizer::unsupported(gf); !why.empty()) {
    fieldFallback_ = why;
    return false;
  }
  fieldFallback_.clear();
  GpuPolygonizeSettings gs;
  gs.resolution = res;
  gs.bounds = field->bounds;
  gs.noiseAmplitude = field->noiseAmplitude;
  gs.noiseFrequency = field->noiseFrequency;
  // A kind of shape whose pipelines are not compiled yet: compile them in the background while the
  // CPU worker draws it (update(); the frame would otherwise stall ~1 s on lavapipe); retried every frame.
  // A screenshot (settle) waits for them instead: it must show this shape.
  compiling_ = !s.settle && !poly_->ready(gf, gs);
  if (compiling_) {
    poly_->prewarm(gf, gs);
    deferred_ = true;
    deferredSource_ = source;
    return true;
  }
  VkDevice dev = ctx_.device();
  if (s.settle) {
    // A screenshot: the whole shape in this frame. A record reads its counters frames later, so
    // the first record of a shape that outgrows the buffers would draw nothing; the synchronous
    // polygonisation grows them and redoes it until the mesh fits (after this preview's own
    // records, which use the same buffers).
    for (uint32_t i = 0; i < kFramesInFlight; ++i)
      if (pending_[i] && vkWaitForFences(dev, 1, &fences_[i], VK_TRUE, UINT64_MAX) != VK_SUCCESS) {
        gpuFailure_ = "GPU preview: waiting for the GPU failed";
        return false;
      }
    pollGpu();
    Result<GpuPolygonizeStats> done = poly_->polygonize(gf, gs);
    if (!done) {
      gpuFailure_ = "GPU preview: " + done.error();
      return false;
    }
    gpuShownMs_ = done->milliseconds;
    gpuShownRes_ = res;
    gpuDrawnTime_ = timeSec;
    gpuSource_ = source;
    gpuResolution_ = res;
    settled_ = true;
    gpuDrawable_ = true;
    return true;
  }
  const uint32_t slot = uint32_t(serial_ % kFramesInFlight);
  // The record kFramesInFlight ago used this slot; GpuPolygonizer::record reads its counters.
  if (pending_[slot]) {
    VkResult w = vkWaitForFences(dev, 1, &fences_[slot], VK_TRUE, UINT64_MAX);
    if (w != VK_SUCCESS) {
      gpuFailure_ = "GPU preview: " + std::string(vkResultName(w));
      return false;
    }
    pollGpu();
  }
  VkCommandBuffer cmd = cmds_[slot];
  vkResetCommandBuffer(cmd, 0);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &bi);
  Status st = poly_->record(cmd, serial_, gf, gs);
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
  submittedRes_[slot] = res;
  gpuDrawnTime_ = timeSec;
  lastUpdateRecorded_ = true;
  ++serial_;
  ++recordsOfShape_;
  // Normally the next frame settles it (recordFitted, above). Records that overflowed again are
  // also read kFramesInFlight records later inside record(): once those of a record of this shape
  // show it fitted, the records since fit too.
  settled_ = recordsOfShape_ > int(kFramesInFlight) && !poly_->lastStats().overflowed;
  gpuSource_ = source;
  gpuResolution_ = res;
  gpuDrawable_ = true;
  return true;
}

void ImplicitPreview::draw(Scene& scene, const glm::mat4& model, const glm::vec4& color, bool selected) const {
  if (usingGpu() && !(cpuFillIn_ && mesh_)) {
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
    return deferred_ || refineHeld_ || !settled_;
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
    bool idle = !compiling_ || poly_->waitForCompilation(timeoutSec);  // the next update records it
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
