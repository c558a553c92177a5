#include "app/cli/bench/bench_gpu_transition.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>

#include "gpu/vulkan/context.h"
#include "core/scene/transition_frame.h"
#include "gpu/present/offscreen_target.h"
#include "core/rig/pose.h"
#include "gpu/render/scene_renderer.h"
#include "gpu/transition/transition_evaluator.h"

namespace animorph::bench {

namespace {

double processCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Medians over pairs of frames a and b drawn at the same pose (pose(k) before pair k), in
// alternating order (a, b; b, a; ...) so that neither always runs second: wall and processor time
// (the process's, llvmpipe's rendering threads included) of each.
struct PairTimes {
  double wallA = 0, wallB = 0, cpuA = 0, cpuB = 0;
};
template <class Pose, class A, class B>
PairTimes pairedMedians(int pairs, Pose&& pose, A&& a, B&& b) {
  std::vector<double> wa, wb, ca, cb;
  auto timed = [](auto&& fn, std::vector<double>& wall, std::vector<double>& cpu) {
    const double c0 = processCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(processCpuMs() - c0);
  };
  for (int k = 0; k < pairs; ++k) {
    pose(k);
    if (k % 2 == 0) {
      timed(a, wa, ca);
      timed(b, wb, cb);
    } else {
      timed(b, wb, cb);
      timed(a, wa, ca);
    }
  }
  return {medianOf(wa), medianOf(wb), medianOf(ca), medianOf(cb)};
}

// The same binding with colours (a textured colour per vertex and the stand-in's), as a coloured
// character's: the shader then unpacks and fades the colour too.
StandinBinding colouredCopy(const StandinBinding& binding) {
  StandinBinding out = binding;
  out.vertexColors.resize(binding.offsets.size());
  out.standinColors.resize(binding.offsets.size());
  for (size_t i = 0; i < binding.offsets.size(); ++i) {
    const glm::vec3 n = binding.standinNormals[i];
    out.vertexColors[i] = glm::vec4(0.5f + 0.5f * n, 1.0f);
    out.standinColors[i] = glm::vec4(0.5f - 0.5f * n, 1.0f);
  }
  return out;
}

// The vertex work alone: the compute twin of the shader (its mesh set), submitted and waited for,
// at alpha 0.5 and re-projected at 0.84.
void computeTwinRows(const Options& opt, const Character& c, int node, const MorphRuntime& rt,
                     gpu::TransitionEvaluator& evaluator, std::vector<Row>& rows) {
  std::vector<glm::vec3> pos, nrm;
  const auto globals = poseGlobals(c, rt.source.clip, 0.5f);
  const auto j = jointMatrices(c, node, globals);
  char note[240];
  for (double u : {0.5, 0.75}) {
    const TransitionFrame f = transitionFrame(rt, false, 0.5, u, true);
    (void)evaluator.evaluate(j, globals[size_t(node)], f, pos, nrm);  // warm-up
    const double ms = medianMs(opt.quick ? 3 : 9, [&] { (void)evaluator.evaluate(j, globals[size_t(node)], f, pos, nrm); });
    std::snprintf(note, sizeof note, "compute twin of the vertex shader, %zu vertices, alpha %s; wall time with "
                  "submit, wait and read-back (GPU timestamps say %.3f ms)", pos.size(),
                  u == 0.5 ? "0.5" : "0.84, re-projected", evaluator.lastDispatchMs());
    rows.push_back({u == 0.5 ? "transition vertices (GPU compute)" : "transition vertices re-projected (GPU compute)",
                    ms, "ms", "", note});
  }
}

}  // namespace

std::vector<Row> gpuTransitionRows(const Options& opt, const Character& c, const Standin& standin,
                                   const StandinBinding& binding) {
  using namespace animorph::gpu;
  std::vector<Row> rows;
  if (!opt.gpu) return {{"GPU transition", 0.0, "", "", "skipped: run with --gpu"}};
  auto ctx = Context::create(ContextSettings{});
  if (!ctx) return {{"GPU transition", 0.0, "", "", "no Vulkan device: " + ctx.error()}};
  const uint32_t width = 1280, height = 720;
  auto target = OffscreenTarget::create(**ctx, width, height);
  if (!target) return {{"GPU transition", 0.0, "", "", target.error()}};
  auto renderer = SceneRenderer::create(**ctx, (*target)->renderPass());
  if (!renderer) return {{"GPU transition", 0.0, "", "", renderer.error()}};
  auto evaluator = TransitionEvaluator::create(**ctx);
  if (!evaluator) return {{"GPU transition", 0.0, "", "", evaluator.error()}};
  const int node = c.meshNodes().front();
  const Mesh& mesh = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
  auto gpuMesh = GpuMesh::upload(**ctx, mesh);
  auto gpuBinding = GpuStandinBinding::upload(**ctx, binding, {});
  auto gpuColoured = GpuStandinBinding::upload(**ctx, colouredCopy(binding), {});
  if (!gpuMesh || !gpuBinding || !gpuColoured) return {{"GPU transition", 0.0, "", "", "upload failed"}};

  // A runtime around the character, so the frame parameters come from the editor's code.
  MorphRuntime rt;
  rt.source.character = std::make_shared<Character>(c);
  rt.source.clip = c.clips.empty() ? nullptr : &rt.source.character->clips[0];
  rt.source.morph.standin = standin;
  rt.source.binding = binding;
  rt.source.vertexCount = mesh.vertexCount();

  OrbitCamera camera;
  camera.frame(mesh.bounds(), float(width) / float(height));
  float t = 0.0f;
  Status failure;
  std::vector<glm::mat4> joints;
  TransitionFrame frameParams;
  bool holdPose = false;  // paired frames: the pose set by the pair, not advanced per frame
  auto frame = [&](bool transition, double u, bool coloured = false) {
    if (!holdPose) t += 0.04f;
    const auto globals = poseGlobals(c, rt.source.clip, t);
    joints = jointMatrices(c, node, globals);
    Scene scene;
    scene.options.grid = false;
    scene.options.axisIndicator = false;
    MeshDraw d;
    d.mesh = gpuMesh->get();
    d.model = globals[size_t(node)];
    d.jointMatrices = joints;
    if (transition) {
      frameParams = transitionFrame(rt, false, t, u, true);  // part of the frame's cost
      scene.transitionMeshes.push_back({d, (coloured ? gpuColoured : gpuBinding)->get(), 0, &frameParams});
    } else {
      scene.meshes.push_back(d);
    }
    Status s = (*target)->render(
        [&](VkCommandBuffer cmd) {
          Status r = (*renderer)->record(cmd, (*target)->serial(), {0, 0, width, height}, camera, scene);
          if (!r) failure = r;
        },
        {0, 0, 0, 1}, false);
    if (!s) failure = s;
  };
  const int repeats = opt.quick ? 5 : 21;
  frame(false, 0.0);  // pipelines compile lazily: warm both up
  frame(true, 0.5);
  frame(true, 0.75);
  frame(true, 0.5, true);
  const double skinMs = medianMs(repeats, [&] { frame(false, 0.0); });
  // With and without colour in pairs at the same pose (the pose changes the pixels drawn: medians
  // of separate runs at different poses differed by more than the colour costs).
  holdPose = true;
  const PairTimes colourPairs = pairedMedians(
      opt.quick ? 9 : 21, [&](int) { t += 0.04f; }, [&] { frame(true, 0.5); }, [&] { frame(true, 0.5, true); });
  holdPose = false;
  const double transMs = colourPairs.wallA, colourMs = colourPairs.wallB;
  const double reprojMs = medianMs(opt.quick ? 3 : 9, [&] { frame(true, 0.75); });
  if (!failure) return {{"GPU transition", 0.0, "", "", failure.error()}};
  char note[240];
  std::snprintf(note, sizeof note, "%zu vertices, %ux%u offscreen frame, alpha 0.5; plain skinned draw %.2f ms (%.2fx); %s",
                mesh.vertexCount(), width, height, skinMs, transMs / skinMs, (*ctx)->deviceName().c_str());
  rows.push_back({"transition frame (GPU vertex shader)", transMs, "ms", "~ a skinned draw", note});
  std::snprintf(note, sizeof note, "alpha 0.5, the stand-in colour unpacked and faded per vertex and pixel; "
                "without (the pipeline specialised without colour) at the same poses %.2f ms (%+.1f %%), "
                "latency of one frame, median of %d pairs",
                transMs, 100.0 * (colourMs / transMs - 1.0), opt.quick ? 9 : 21);
  rows.push_back({"transition frame with colour (GPU)", colourMs, "ms", "<= 1.1x without colour", note});
  std::snprintf(note, sizeof note, "processor time of the process (llvmpipe's threads included) per frame: "
                "%.2f ms with colour, %.2f ms without, the same pairs", colourPairs.cpuB, colourPairs.cpuA);
  rows.push_back({"transition frame colour cost in processor time (GPU)",
                  100.0 * (colourPairs.cpuB / colourPairs.cpuA - 1.0), "%", "<= 10 %", note});
  std::snprintf(note, sizeof note, "alpha 0.84: every vertex re-projected in the vertex shader");
  rows.push_back({"transition frame with re-projection (GPU)", reprojMs, "ms", "", note});

  if ((*evaluator)->setMesh(mesh, **gpuBinding, 0)) computeTwinRows(opt, c, node, rt, **evaluator, rows);
  return rows;
}

}  // namespace animorph::bench
