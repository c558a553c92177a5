// The kept viewport image's test for "the scene did not change" (gpu/render/scene_fingerprint.h):
// every change a frame can make to what the viewport shows changes the fingerprint, and draws whose
// content it cannot see make the scene one to draw every frame.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/render/scene_fingerprint.h"
#include "gpu_fixture.h"

using namespace animorph;

namespace {

struct PosedScene {
  std::vector<glm::mat4> joints{glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f))};
  std::vector<float> morphWeights{0.25f};
  gpu::Scene scene;
  PosedScene() {
    gpu::MeshDraw d;
    d.jointMatrices = joints;
    d.morphWeights = morphWeights;
    scene.meshes.push_back(d);
    scene.lines.line(glm::vec3(0.0f), glm::vec3(1.0f), 0xff0000ffu);
  }
};

uint64_t fingerprint(const gpu::Scene& s, const OrbitCamera& cam = {}, uint32_t w = 800, uint32_t h = 600) {
  auto fp = gpu::sceneFingerprint(s, cam, w, h);
  REQUIRE(fp.has_value());
  return *fp;
}

}  // namespace

TEST_CASE("the scene fingerprint is stable for the same scene and changes with each thing a frame can change",
          "[viewport_image]") {
  PosedScene a, b;
  const uint64_t base = fingerprint(a.scene);
  CHECK(fingerprint(b.scene) == base);  // same content in other arrays
  OrbitCamera cam;
  cam.orbit(3.0f, 0.0f);
  CHECK(fingerprint(a.scene, cam) != base);
  CHECK(fingerprint(a.scene, {}, 801, 600) != base);
  b.joints[1][3].y = 1.001f;  // a pose
  CHECK(fingerprint(b.scene) != base);
  b.joints[1][3].y = 1.0f;
  CHECK(fingerprint(b.scene) == base);
  b.morphWeights[0] = 0.5f;  // a blend shape
  CHECK(fingerprint(b.scene) != base);
  b.morphWeights[0] = 0.25f;
  b.scene.meshes[0].selected = true;
  CHECK(fingerprint(b.scene) != base);
  b.scene.meshes[0].selected = false;
  b.scene.meshes[0].model = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 0.01f));
  CHECK(fingerprint(b.scene) != base);
  b.scene.meshes[0].model = glm::mat4(1.0f);
  b.scene.options.wireframe = true;
  CHECK(fingerprint(b.scene) != base);
  b.scene.options.wireframe = false;
  b.scene.overlay.line(glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 0xffffffffu);  // the skeleton shown
  CHECK(fingerprint(b.scene) != base);
  b.scene.overlay.clear();
  gpu::ParticleSpheresDraw p;
  p.spheres.push_back(glm::vec4(0.0f, 0.0f, 0.0f, 0.1f));
  b.scene.particles.push_back(p);
  CHECK(fingerprint(b.scene) != base);
  b.scene.particles.clear();
  CHECK(fingerprint(b.scene) == base);
}

TEST_CASE("a scene with GPU-generated meshes or transitions has no fingerprint (drawn every frame)",
          "[viewport_image]") {
  PosedScene a;
  a.scene.generatedMeshes.push_back({});
  CHECK_FALSE(gpu::sceneFingerprint(a.scene, {}, 800, 600).has_value());
  PosedScene b;
  b.scene.transitionMeshes.push_back({});
  CHECK_FALSE(gpu::sceneFingerprint(b.scene, {}, 800, 600).has_value());
}

TEST_CASE("a mesh uploaded again or given materials draws as a different mesh in the fingerprint",
          "[viewport_image]") {
  test::prepareGpuEnvironment();
  auto ctx = test::makeTestContext();
  const Mesh quads = test::twoQuadMesh();
  auto m1 = gpu::GpuMesh::upload(*ctx, quads);
  auto m2 = gpu::GpuMesh::upload(*ctx, quads);
  REQUIRE(m1.ok());
  REQUIRE(m2.ok());
  CHECK((*m1)->contentSerial() != (*m2)->contentSerial());
  gpu::Scene s;
  gpu::MeshDraw d;
  d.mesh = m1->get();
  s.meshes.push_back(d);
  const uint64_t before = fingerprint(s);
  CHECK(fingerprint(s) == before);
  const uint64_t serial = (*m1)->contentSerial();
  (*m1)->setMaterials({}, {});
  CHECK((*m1)->contentSerial() != serial);
  CHECK(fingerprint(s) != before);
  s.meshes[0].mesh = m2->get();
  CHECK(fingerprint(s) != before);
}
