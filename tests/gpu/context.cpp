// Context creation, device choice and validation reporting.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "gpu/vulkan/buffer.h"
#include "gpu/vulkan/device_select.h"
#include "gpu_fixture.h"
#include "gpu/render/gpu_mesh.h"
#include "gpu/render/line_batch.h"
#include "gpu/present/swapchain.h"

using namespace animorph;
using namespace animorph::gpu;

TEST_CASE("device choice prefers discrete > integrated > virtual > CPU", "[gpu][device]") {
  std::vector<DeviceCandidate> d = {{"llvmpipe (LLVM 15)", VK_PHYSICAL_DEVICE_TYPE_CPU, true},
                                    {"Intel UHD 630", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, true},
                                    {"NVIDIA RTX 4070", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, true},
                                    {"virtio", VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU, true}};
  CHECK(*pickPhysicalDevice(d, "") == 2);
  d[2].usable = false;  // no graphics queue: never picked
  CHECK(*pickPhysicalDevice(d, "") == 1);
  d.erase(d.begin() + 1, d.begin() + 3);
  CHECK(*pickPhysicalDevice(d, "") == 1);  // virtual over CPU
  d.pop_back();
  CHECK(*pickPhysicalDevice(d, "") == 0);
}

TEST_CASE("ANIMORPH_GPU picks by index or name substring, never silently falls back", "[gpu][device]") {
  std::vector<DeviceCandidate> d = {{"llvmpipe (LLVM 15)", VK_PHYSICAL_DEVICE_TYPE_CPU, true},
                                    {"NVIDIA RTX 4070", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, true}};
  CHECK(*pickPhysicalDevice(d, "0") == 0);
  CHECK(*pickPhysicalDevice(d, "LLVMpipe") == 0);  // case-insensitive
  CHECK(*pickPhysicalDevice(d, "rtx") == 1);
  auto missing = pickPhysicalDevice(d, "radeon");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().find("ANIMORPH_GPU=radeon") != std::string::npos);
  CHECK(missing.error().find("llvmpipe") != std::string::npos);  // lists what exists
  CHECK(missing.error().find("NVIDIA RTX 4070") != std::string::npos);
  CHECK_FALSE(pickPhysicalDevice(d, "7").ok());
  auto none = pickPhysicalDevice({}, "");
  REQUIRE_FALSE(none.ok());
  CHECK(none.error().find("mesa-vulkan-drivers") != std::string::npos);
}

TEST_CASE("headless context on lavapipe", "[gpu][context]") {
  auto ctx = test::makeTestContext();
  CHECK(ctx->headless());
  CHECK_FALSE(ctx->deviceName().empty());
  CHECK(ctx->device() != VK_NULL_HANDLE);
  CHECK(ctx->uiDescriptorPool() != VK_NULL_HANDLE);
  CHECK(ctx->depthFormat() != VK_FORMAT_UNDEFINED);
  // A swapchain needs a window.
  auto sc = Swapchain::create(*ctx);
  REQUIRE_FALSE(sc.ok());
  CHECK(sc.error().find("without a window") != std::string::npos);
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("ANIMORPH_GPU=nonexistent-device gives a clear error", "[gpu][context]") {
  test::prepareGpuEnvironment();
  setenv("ANIMORPH_GPU", "nonexistent-device", 1);
  ContextSettings settings;  // reads ANIMORPH_GPU
  unsetenv("ANIMORPH_GPU");
  CHECK(settings.deviceOverride == "nonexistent-device");
  auto ctx = Context::create(settings);
  REQUIRE_FALSE(ctx.ok());
  CHECK(ctx.error().find("ANIMORPH_GPU=nonexistent-device") != std::string::npos);
  CHECK(ctx.error().find("matches no usable Vulkan device") != std::string::npos);
  // By index: device 0 exists.
  settings.deviceOverride = "0";
  auto byIndex = Context::create(settings);
  INFO(byIndex.error());
  CHECK(byIndex.ok());
}

TEST_CASE("validation errors are counted", "[gpu][context]") {
  test::prepareGpuEnvironment();
  ContextSettings settings;
  settings.validation = true;
  settings.printValidationMessages = false;
  settings.deviceOverride.clear();
  auto ctx = Context::create(settings);
  REQUIRE(ctx.ok());
  REQUIRE((*ctx)->validationEnabled());
  CHECK((*ctx)->validationErrorCount() == 0);
  // A deliberate misuse: a zero-sized buffer (VUID-VkBufferCreateInfo-size-00912).
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, 0, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                         VK_SHARING_MODE_EXCLUSIVE, 0, nullptr};
  VkBuffer buffer = VK_NULL_HANDLE;
  VkResult r = vkCreateBuffer((*ctx)->device(), &bci, nullptr, &buffer);
  if (r == VK_SUCCESS && buffer) vkDestroyBuffer((*ctx)->device(), buffer, nullptr);
  CHECK((*ctx)->validationErrorCount() >= 1);
}

TEST_CASE("mesh upload rejects bad meshes with the mesh name", "[gpu][mesh]") {
  auto ctx = test::makeTestContext();
  Mesh m = test::twoQuadMesh();
  m.indices[4] = 99;
  auto bad = GpuMesh::upload(*ctx, m);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("two quads") != std::string::npos);
  CHECK(bad.error().find("out of range") != std::string::npos);
  Mesh empty;
  empty.name = "nothing";
  CHECK_FALSE(GpuMesh::upload(*ctx, empty).ok());
  // Without normals and joints: normals computed, every vertex on joint 0; edges on request.
  Mesh plain = test::twoQuadMesh();
  plain.normals.clear();
  plain.joints0.clear();
  plain.weights0.clear();
  plain.joints1.clear();
  plain.weights1.clear();
  auto ok = GpuMesh::upload(*ctx, plain, true);
  REQUIRE(ok.ok());
  CHECK((*ok)->vertexCount() == 8);
  CHECK((*ok)->indexCount() == 12);
  CHECK((*ok)->edgeIndexCount() == 2 * 10);  // two quads of 5 unique edges
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("line batches: octahedra, boxes, skeletons", "[gpu][lines]") {
  LineBatch b;
  b.octahedron({0, 0, 0}, 1.0f, packRgba({1, 0, 0, 1}));
  CHECK(b.segmentCount() == 12);
  for (const auto& v : b.vertices()) CHECK(glm::length(v.position) == Approx(1.0f));
  b.clear();
  Bounds box;
  box.add({0, 0, 0});
  box.add({1, 2, 3});
  b.box(box, 0);
  CHECK(b.segmentCount() == 12);
  CHECK(packRgba({1, 0.5f, 0, 1}) == (255u | (128u << 8) | (255u << 24)));

  Character c;
  c.nodes.resize(3);
  c.nodes[0].children = {1};
  c.nodes[1].parent = 0;
  c.nodes[1].children = {2};
  c.nodes[2].parent = 1;
  c.skins.push_back(Skin{"s", {0, 1}, {}, 0});  // node 2 is not a joint
  std::vector<glm::mat4> globals(3, glm::mat4(1.0f));
  globals[1][3] = glm::vec4(0, 1, 0, 1);
  b.clear();
  addSkeleton(b, c, globals, 0.1f, 1u, 2u);
  CHECK(b.segmentCount() == 2 * 12 + 1);  // two joint markers and one bone
  size_t bones = 0;
  for (size_t i = 0; i < b.vertices().size(); i += 2)
    if (b.vertices()[i].rgba == 1u) {
      ++bones;
      CHECK(glm::length(b.vertices()[i].position - glm::vec3(0, 0, 0)) < 1e-6f);
      CHECK(glm::length(b.vertices()[i + 1].position - glm::vec3(0, 1, 0)) < 1e-6f);
    }
  CHECK(bones == 1);
}
