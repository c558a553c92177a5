// Blend shapes in the skinned vertex shader (shaders/include/morph_targets.glsl)
// against the CPU path (rig/skinning.h): the GPU-morphed and skinned mesh renders
// as the CPU-morphed and skinned mesh drawn rigidly does, on lavapipe with
// validation on.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu_fixture.h"
#include "core/rig/skinning.h"
#include "gpu/render/scene_renderer.h"
#include "shared_constants.h"

using namespace animorph;
using namespace animorph::gpu;

namespace {

const glm::vec4 kBackground{0.1f, 0.2f, 0.3f, 1.0f};
const glm::vec4 kRed{0.85f, 0.2f, 0.15f, 1.0f};

OrbitCamera frontCamera() {
  OrbitCamera c;
  c.target = glm::vec3(0.0f, 0.4f, 0.0f);
  c.yawRad = 0.3f;
  c.pitchRad = 0.2f;
  c.distanceM = 6.0f;
  return c;
}

// The two test quads with two targets: "lift" raises quad B (vertices 4..7) and
// tilts its normals, "slide" moves quad A (0..3) right and one corner out of plane.
Mesh morphedQuads() {
  Mesh m = test::twoQuadMesh();
  const size_t n = m.vertexCount();
  MorphTarget lift{"lift", std::vector<glm::vec3>(n, glm::vec3(0.0f)), std::vector<glm::vec3>(n, glm::vec3(0.0f))};
  MorphTarget slide{"slide", std::vector<glm::vec3>(n, glm::vec3(0.0f)), {}};
  for (size_t v = 4; v < 8; ++v) {
    lift.positionDeltas[v] = glm::vec3(0.0f, 0.6f, 0.1f * float(v - 4));
    lift.normalDeltas[v] = glm::vec3(0.6f, 0.0f, 0.0f);
  }
  for (size_t v = 0; v < 4; ++v) slide.positionDeltas[v] = glm::vec3(0.4f, 0.0f, v == 2 ? 0.5f : 0.0f);
  m.morphTargets = {lift, slide};
  return m;
}

std::vector<glm::mat4> bendJoints() {
  std::vector<glm::mat4> j(6, glm::mat4(1.0f));
  j[1] = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.5f, 0)), 0.4f, glm::vec3(0, 0, 1));
  return j;
}

Scene oneDraw(const GpuMesh* mesh, std::span<const glm::mat4> joints, std::span<const float> weights) {
  Scene s;
  s.options.background = kBackground;
  s.options.grid = false;
  s.options.axisIndicator = false;
  MeshDraw d;
  d.mesh = mesh;
  d.jointMatrices = joints;
  d.morphWeights = weights;
  d.color = kRed;
  s.meshes.push_back(d);
  return s;
}

// Pixels whose colour differs between a and b by more than tolerance in a channel.
size_t pixelsApart(const RgbaImage& a, const RgbaImage& b, int tolerance) {
  size_t n = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      const glm::ivec4 d = glm::abs(glm::ivec4(a.at(x, y)) - glm::ivec4(b.at(x, y)));
      n += std::max({d.r, d.g, d.b}) > tolerance;
    }
  return n;
}

}  // namespace

TEST_CASE("GPU blend shapes: morphed and skinned meshes render as the CPU morphs and skins them", "[gpu][render][blendshape]") {
  auto ctx = test::makeTestContext();
  test::SceneTarget draw = test::makeSceneTarget(*ctx, 320, 240);
  const Mesh mesh = morphedQuads();
  auto gpuMesh = GpuMesh::upload(*ctx, mesh);
  INFO(gpuMesh.error());
  REQUIRE(gpuMesh.ok());
  CHECK((*gpuMesh)->morphTargetCount() == 2);
  const std::vector<glm::mat4> joints = bendJoints();
  const OrbitCamera cam = frontCamera();
  for (const std::vector<float>& weights : {std::vector<float>{1.0f, 0.0f}, std::vector<float>{0.5f, 1.0f},
                                            std::vector<float>{-0.5f, 0.75f}}) {
    INFO("weights " << weights[0] << ", " << weights[1]);
    // The CPU's result as a rigid mesh: positions and normals already morphed and skinned.
    Mesh cpu = mesh;
    skinMesh(mesh, joints, cpu.positions, cpu.normals, weights);
    cpu.morphTargets.clear();
    cpu.joints0.clear(), cpu.weights0.clear(), cpu.joints1.clear(), cpu.weights1.clear();
    auto cpuGpu = GpuMesh::upload(*ctx, cpu);
    REQUIRE(cpuGpu.ok());
    const std::vector<glm::mat4> identity{glm::mat4(1.0f)};
    const RgbaImage reference = test::renderScene(draw, cam, oneDraw(cpuGpu->get(), identity, {}));
    const RgbaImage morphed = test::renderScene(draw, cam, oneDraw(gpuMesh->get(), joints, weights));
    const RgbaImage unmorphed = test::renderScene(draw, cam, oneDraw(gpuMesh->get(), joints, {}));
    const size_t covered = test::countDiffering(reference, kBackground, 3);
    REQUIRE(covered > 2000);
    const size_t apart = pixelsApart(morphed, reference, 6);
    // Rasterisation of the same triangles from two float paths: edge pixels at most.
    CHECK(apart < covered / 50);
    // Without the weights the picture is another one: the comparison can fail.
    CHECK(pixelsApart(unmorphed, reference, 6) > 10 * apart + covered / 20);
  }
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU blend shapes: a draw with more active targets than the limit keeps the largest weights", "[gpu][render][blendshape]") {
  auto ctx = test::makeTestContext();
  test::SceneTarget draw = test::makeSceneTarget(*ctx, 200, 150);
  // kMaxActiveMorphTargets + 8 targets: the small ones each move quad A by a tiny amount, the last one lifts quad B.
  Mesh mesh = test::twoQuadMesh();
  const size_t n = mesh.vertexCount(), targets = kMaxActiveMorphTargets + 8;
  std::vector<float> weights(targets, 0.001f);
  for (size_t t = 0; t < targets; ++t) {
    MorphTarget mt{"t" + std::to_string(t), std::vector<glm::vec3>(n, glm::vec3(0.0f)), {}};
    if (t + 1 == targets)
      for (size_t v = 4; v < 8; ++v) mt.positionDeltas[v] = glm::vec3(0.0f, 1.0f, 0.0f);
    else
      for (size_t v = 0; v < 4; ++v) mt.positionDeltas[v] = glm::vec3(0.001f, 0.0f, 0.0f);
    mesh.morphTargets.push_back(std::move(mt));
  }
  weights.back() = 1.0f;
  auto gpuMesh = GpuMesh::upload(*ctx, mesh);
  REQUIRE(gpuMesh.ok());
  const std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  OrbitCamera cam;
  cam.target = glm::vec3(0.0f, 0.5f, 0.0f);
  cam.distanceM = 6.0f;
  const RgbaImage& img = test::renderScene(draw, cam, oneDraw(gpuMesh->get(), joints, weights));
  // The lifting target has the largest weight: it is among those drawn.
  CHECK(test::differs(test::pixelAt(img, cam, {1.0f, 1.0f, 0.0f}), kBackground, 10));
  CHECK_FALSE(test::differs(test::pixelAt(img, cam, {1.0f, -0.3f, 0.0f}), kBackground, 3));
  CHECK(ctx->validationErrorCount() == 0);
}
