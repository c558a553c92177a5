// Benchmark: offscreen render of a ~50k-triangle skinned mesh at 1600x900 —
// median ms per frame (record + submit + wait), with and without read-back,
// and the first-frame cost (pipeline creation and lazy shader compilation).
#include <chrono>

#include <sys/resource.h>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "app/cli/bench/bench.h"
#include "gpu/vulkan/context.h"
#include "gpu/present/offscreen_target.h"
#include "gpu/render/scene_renderer.h"

namespace {

using namespace animorph;
using namespace animorph::gpu;

// CPU time of the whole process (all of lavapipe's threads) in ms: on a shared
// machine it varies less than wall time.
double processCpuMs() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 + double(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// A closed-ish tube along +Y over `joints` joints; each vertex blends the two
// nearest joints, and every fourth ring spreads over 8 (both influence sets).
Mesh skinnedTube(int rings, int segments, int joints) {
  Mesh m;
  m.name = "bench tube";
  const float length = 2.0f, radius = 0.2f;
  for (int i = 0; i <= rings; ++i) {
    float t = float(i) / float(rings);
    float jf = t * float(joints - 1);
    uint32_t j0 = std::min(uint32_t(jf), uint32_t(joints - 2));
    float w = jf - float(j0);
    for (int s = 0; s < segments; ++s) {
      float a = 6.2831853f * float(s) / float(segments);
      m.positions.push_back({radius * std::cos(a), t * length, radius * std::sin(a)});
      m.normals.push_back({std::cos(a), 0.0f, std::sin(a)});
      if (i % 4 == 0) {
        m.joints0.push_back({j0, j0 + 1, 0, uint32_t(joints - 1)});
        m.weights0.push_back({0.5f * (1 - w), 0.5f * w, 0.1f, 0.1f});
        m.joints1.push_back({j0, j0 + 1, 1, 2});
        m.weights1.push_back({0.1f, 0.1f, 0.05f, 0.05f});
      } else {
        m.joints0.push_back({j0, j0 + 1, 0, 0});
        m.weights0.push_back({1 - w, w, 0, 0});
        m.joints1.push_back({0, 0, 0, 0});
        m.weights1.push_back({0, 0, 0, 0});
      }
    }
  }
  for (int i = 0; i < rings; ++i)
    for (int s = 0; s < segments; ++s) {
      uint32_t a = uint32_t(i * segments + s), b = uint32_t(i * segments + (s + 1) % segments);
      uint32_t c = a + uint32_t(segments), d = b + uint32_t(segments);
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  return m;
}

std::vector<glm::mat4> bendJoints(int joints, float angle) {
  std::vector<glm::mat4> out(joints);
  glm::mat4 parent(1.0f);
  const float step = 2.0f / float(joints - 1);
  for (int j = 0; j < joints; ++j) {
    // Each joint bends by angle about Z at its rest height; skin matrix = global * inverseBind.
    glm::mat4 local = j == 0 ? glm::mat4(1.0f)
                             : glm::translate(glm::mat4(1.0f), glm::vec3(0, step, 0)) *
                                   glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 0, 1));
    parent = parent * local;
    out[j] = parent * glm::translate(glm::mat4(1.0f), glm::vec3(0, -step * float(j), 0));
  }
  return out;
}

std::vector<bench::Row> runRenderBench(const bench::Options& opt) {
  if (!opt.gpu) return {{"skipped", 0.0, "", "", "GPU benchmark: run with --gpu"}};
  const uint32_t width = opt.quick ? 640 : 1600, height = opt.quick ? 360 : 900;
  const int rings = opt.quick ? 96 : 390, segments = 64, jointCount = 8;

  auto t0 = std::chrono::steady_clock::now();
  ContextSettings settings;
  auto ctx = Context::create(settings);
  if (!ctx) return {{"context", 0.0, "", "", "no Vulkan device: " + ctx.error()}};
  const double contextMs = msSince(t0);
  auto target = OffscreenTarget::create(**ctx, width, height);
  if (!target) return {{"target", 0.0, "", "", target.error()}};
  Mesh mesh = skinnedTube(rings, segments, jointCount);
  auto gpuMesh = GpuMesh::upload(**ctx, mesh);
  if (!gpuMesh) return {{"upload", 0.0, "", "", gpuMesh.error()}};

  t0 = std::chrono::steady_clock::now();
  auto renderer = SceneRenderer::create(**ctx, (*target)->renderPass());
  if (!renderer) return {{"renderer", 0.0, "", "", renderer.error()}};
  const double createMs = msSince(t0);

  OrbitCamera camera;
  camera.target = {0, 1, 0};
  camera.distanceM = 4.0f;
  Scene scene;
  std::vector<glm::mat4> joints = bendJoints(jointCount, 0.1f);
  MeshDraw draw;
  draw.mesh = gpuMesh->get();
  draw.jointMatrices = joints;
  scene.meshes.push_back(draw);
  int frame = 0;
  Status failure;
  auto renderFrame = [&](bool readBack) {
    joints = bendJoints(jointCount, 0.15f * std::sin(0.1f * float(frame++)));  // new pose every frame
    scene.meshes[0].jointMatrices = joints;
    Status s = (*target)->render(
        [&](VkCommandBuffer cmd) {
          Status r = (*renderer)->record(cmd, (*target)->serial(), {0, 0, width, height}, camera, scene);
          if (!r) failure = r;
        },
        {0, 0, 0, 1}, readBack);
    if (!s) failure = s;
  };
  t0 = std::chrono::steady_clock::now();
  renderFrame(false);
  const double firstFrameMs = msSince(t0);
  const int repeats = opt.quick ? 5 : 30;
  const double frameMs = bench::medianMs(repeats, [&] { renderFrame(false); });
  const double cpu0 = processCpuMs();
  for (int i = 0; i < repeats; ++i) renderFrame(false);
  const double frameCpuMs = (processCpuMs() - cpu0) / repeats;
  scene.options.grid = false;
  const double noGridMs = bench::medianMs(opt.quick ? 3 : 10, [&] { renderFrame(false); });
  scene.options.grid = true;
  const double readbackMs = bench::medianMs(opt.quick ? 3 : 10, [&] { renderFrame(true); });
  scene.options.wireframe = true;
  const double wireMs = bench::medianMs(opt.quick ? 3 : 10, [&] { renderFrame(false); });
  scene.options.wireframe = false;
  // The particle view (ParticleSpheresDraw): 40,000 spheres of 0.8-1.2 cm (the visible radius of
  // the statue converted to 40,000 particles is 0.9 cm) spread through a 2 m box around the mesh,
  // drawn instead of it (the mesh frame above is the baseline).
  Scene particleScene;
  particleScene.options = scene.options;
  ParticleSpheresDraw spheres;
  const int particleCount = opt.quick ? 4000 : 40000;
  uint32_t state = 12345u;
  auto unit = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  for (int i = 0; i < particleCount; ++i)
    spheres.spheres.push_back({unit() * 2.0f - 1.0f, unit() * 2.0f, unit() * 2.0f - 1.0f, 0.008f + 0.004f * unit()});
  particleScene.particles.push_back(std::move(spheres));
  auto renderParticles = [&] {
    Status s = (*target)->render(
        [&](VkCommandBuffer cmd) {
          Status r = (*renderer)->record(cmd, (*target)->serial(), {0, 0, width, height}, camera, particleScene);
          if (!r) failure = r;
        },
        {0, 0, 0, 1}, false);
    if (!s) failure = s;
  };
  renderParticles();  // first use of its pipeline
  const double particleMs = bench::medianMs(repeats, renderParticles);
  if (!failure) return {{"failed", 0.0, "", "", failure.error()}};

  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string what = std::to_string(mesh.triangleCount()) + " tris, " + std::to_string(mesh.vertexCount()) +
                           " verts, 8 joints, " + size + ", " + (*ctx)->deviceName();
  return {
      {"frame (median)", frameMs, "ms", "", what},
      {"frame CPU time (mean)", frameCpuMs, "ms", "", "process CPU time, all threads: robust to other load"},
      {"frame without grid (median)", noGridMs, "ms", "", "mesh only"},
      {"particle view: " + std::to_string(particleCount) + " spheres (median)", particleMs, "ms", "",
       "instanced ray-cast impostors with depth instead of the mesh (baseline: frame)"},
      {"frame + read-back (median)", readbackMs, "ms", "", size + " RGBA8 to host"},
      {"frame with wireframe (median)", wireMs, "ms", "", (*renderer)->wireframeUsesEdgeLists() ? "edge lists" : "polygon mode line"},
      {"first frame", firstFrameMs, "ms", "", "lazy pipeline compilation on first draw"},
      {"renderer creation", createMs, "ms", "", "7 pipelines"},
      {"context creation", contextMs, "ms", "", (*ctx)->validationEnabled() ? "validation ON (slower)" : "validation off"},
  };
}

}  // namespace

ANIMORPH_BENCH("render", "offscreen render of a ~50k-triangle skinned mesh at 1600x900 (--gpu)", runRenderBench);
