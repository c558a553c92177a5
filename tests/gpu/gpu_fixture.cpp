#include "gpu_fixture.h"

#include <cstdlib>
#include <filesystem>

#include <catch2/catch.hpp>

namespace animorph::test {

void prepareGpuEnvironment() {
  setenv("ANIMORPH_VALIDATION", "1", 1);
  const char* lvp = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
  if (std::filesystem::exists(lvp)) setenv("VK_ICD_FILENAMES", lvp, 0);
}

std::unique_ptr<gpu::Context> makeTestContext() {
  prepareGpuEnvironment();
  gpu::ContextSettings settings;
  settings.validation = true;
  settings.deviceOverride.clear();
  auto ctx = gpu::Context::create(settings);
  INFO(ctx.error());
  REQUIRE(ctx.ok());
  REQUIRE((*ctx)->validationEnabled());  // vulkan-validationlayers is a test dependency (run.sh)
  return std::move(*ctx);
}

SceneTarget makeSceneTarget(gpu::Context& ctx, uint32_t width, uint32_t height, gpu::SceneRendererSettings settings) {
  SceneTarget t;
  auto target = gpu::OffscreenTarget::create(ctx, width, height);
  INFO(target.error());
  REQUIRE(target.ok());
  t.target = std::move(*target);
  auto renderer = gpu::SceneRenderer::create(ctx, t.target->renderPass(), settings);
  INFO(renderer.error());
  REQUIRE(renderer.ok());
  t.renderer = std::move(*renderer);
  return t;
}

const gpu::RgbaImage& renderScene(SceneTarget& t, const OrbitCamera& cam, const gpu::Scene& scene) {
  VkExtent2D e = t.target->extent();
  Status recorded;
  Status s = t.target->render([&](VkCommandBuffer cmd) {
    recorded = t.renderer->record(cmd, t.target->serial(), {0, 0, e.width, e.height}, cam, scene);
  });
  INFO(s.error() + recorded.error());
  REQUIRE(s.ok());
  REQUIRE(recorded.ok());
  REQUIRE(t.target->image().width == e.width);
  return t.target->image();
}

glm::u8vec4 pixelAt(const gpu::RgbaImage& img, const OrbitCamera& cam, const glm::vec3& world) {
  glm::vec3 p = cam.worldToPixel(world, {float(img.width), float(img.height)});
  REQUIRE(p.x >= 0.0f);
  REQUIRE(p.y >= 0.0f);
  REQUIRE(p.x < float(img.width));
  REQUIRE(p.y < float(img.height));
  return img.at(uint32_t(p.x), uint32_t(p.y));
}

Mesh twoQuadMesh() {
  Mesh m;
  m.name = "two quads";
  for (float cx : {-1.0f, 1.0f}) {
    uint32_t base = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {{cx - 0.5f, -0.5f, 0}, {cx + 0.5f, -0.5f, 0}, {cx + 0.5f, 0.5f, 0}, {cx - 0.5f, 0.5f, 0}});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    for (int v = 0; v < 4; ++v) {
      m.normals.push_back({0, 0, 1});
      if (cx < 0) {
        m.joints0.push_back({0, 0, 0, 0});
        m.weights0.push_back({1, 0, 0, 0});
        m.joints1.push_back({0, 0, 0, 0});
        m.weights1.push_back({0, 0, 0, 0});
      } else {
        m.joints0.push_back({2, 3, 4, 5});
        m.weights0.push_back({0.05f, 0.05f, 0.05f, 0.05f});
        m.joints1.push_back({1, 40, 0, 0});
        m.weights1.push_back({0.8f, 0, 0, 0});
      }
    }
  }
  return m;
}

bool differs(glm::u8vec4 p, glm::vec4 c, int tolerance) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(int(p[k]) - int(c[k] * 255.0f + 0.5f)) > tolerance) return true;
  return false;
}

size_t countDiffering(const gpu::RgbaImage& image, glm::vec4 c, int tolerance) {
  size_t n = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) n += differs(image.at(x, y), c, tolerance);
  return n;
}

}  // namespace animorph::test
