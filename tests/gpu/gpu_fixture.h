#pragma once
// Shared set-up of the GPU tests: a headless context on lavapipe with
// validation on, and a small skinned test mesh.
#include <memory>

#include "gpu/vulkan/context.h"
#include "core/rig/character.h"
#include "gpu/present/offscreen_target.h"
#include "gpu/present/rgba_image.h"
#include "gpu/render/scene_renderer.h"
#include "core/camera/camera.h"

namespace animorph::test {

// Sets ANIMORPH_VALIDATION=1 and, unless already set, pins the lavapipe ICD.
void prepareGpuEnvironment();

// A headless context with validation (REQUIREs success and that the validation layer is on).
std::unique_ptr<gpu::Context> makeTestContext();

// Two unit quads in the plane z = 0 facing +Z, 4 vertices and 2 triangles each:
// quad A centred at (-1, 0, 0) bound to joint 0; quad B centred at (1, 0, 0)
// spread over 8 influences: 0.05 each on joints 2..5 (JOINTS_0) and 0.8 on
// joint 1 (JOINTS_1), plus a zero weight on an out-of-range joint.
Mesh twoQuadMesh();

// An offscreen target and a scene renderer drawing into it.
struct SceneTarget {
  std::unique_ptr<gpu::OffscreenTarget> target;
  std::unique_ptr<gpu::SceneRenderer> renderer;
};
SceneTarget makeSceneTarget(gpu::Context& ctx, uint32_t width, uint32_t height,
                            gpu::SceneRendererSettings settings = {});

// Draws scene through cam over the whole target and reads it back (REQUIREs success); the image
// lives in the target until its next render.
const gpu::RgbaImage& renderScene(SceneTarget& t, const OrbitCamera& cam, const gpu::Scene& scene);

// The pixel world projects to (REQUIREs it inside the image).
glm::u8vec4 pixelAt(const gpu::RgbaImage& img, const OrbitCamera& cam, const glm::vec3& world);

// True when pixel p differs from colour c by more than tolerance in some channel.
bool differs(glm::u8vec4 p, glm::vec4 c, int tolerance = 3);

// Number of pixels differing from colour c (see differs()).
size_t countDiffering(const gpu::RgbaImage& image, glm::vec4 c, int tolerance = 3);

}  // namespace animorph::test
