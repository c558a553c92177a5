// The vertex-shader transition (shaders/include/transition.glsl) against the
// CPU transition (standin_morph/transition.h) on lavapipe: positions through the
// compute twin of the shader for several u (0, mid, re-projected, 1), on the
// demo creature / gear and a shared Blender asset, with and without a painted
// weight map; the drawn image at alpha = 0 equals plain skinning's exactly;
// the dithered cross-fade covers complementary pixels.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include "gpu_fixture.h"
#include "core/io/gltf_import.h"
#include "core/project/new_morph_project.h"
#include "core/scene/transition_frame.h"
#include "gpu/present/offscreen_target.h"
#include "core/rig/pose.h"
#include "core/scene/mesh_character.h"
#include "core/scene/scene_frame.h"
#include "gpu/render/scene_renderer.h"
#include "gpu/transition/transition_evaluator.h"
#include "util/morph_fixtures.h"
#include "util/test_skip.h"

using namespace animorph;
using namespace animorph::gpu;

namespace {

struct Comparison {
  double maxDistance = 0.0;     // metres, worst vertex
  double maxNormalAngle = 0.0;  // radians, among vertices within tolerance
  double diagonal = 0.0;
  size_t vertices = 0;
  size_t apart = 0;  // vertices further apart than 1e-5 of the diagonal
  float apartGpuField = 0.0f, apartCpuField = 0.0f;  // largest |f| on the posed stand-in among those
  std::vector<glm::vec3> gpuPositions;
};

// GPU (compute twin of transition.vert) vs CPU positions of actor (target when
// expand) at scene time timeSec and stage progress u.
Comparison compareWithCpu(Context& ctx, TransitionEvaluator& ev, const MorphRuntime& rt, bool expand, double timeSec,
                          double u) {
  const MorphActorRuntime& a = expand ? rt.target : rt.source;
  const Character& c = *a.character;
  MorphFrameSettings fs;
  const MorphFrame cpu = evaluateMorphTransition(rt, timeSec, expand, u, fs);
  auto binding = GpuStandinBinding::upload(ctx, a.binding, a.morph.weightMap);
  INFO(binding.error());
  REQUIRE(binding.ok());
  const TransitionFrame tf = transitionFrame(rt, expand, timeSec, u, true);
  const float clipT = a.clip ? float(actorClipTimeSec(a.actor, *a.clip, timeSec)) : 0.0f;
  const auto globals = poseGlobals(c, a.clip, clipT);
  const glm::mat4 root = a.actor.transform.matrix();
  Comparison out;
  std::vector<double> dist;
  size_t first = 0;
  Bounds box;
  for (int node : c.meshNodes()) {
    const Mesh& mesh = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
    REQUIRE(ev.setMesh(mesh, **binding, uint32_t(first)).ok());
    const auto joints = jointMatrices(c, node, globals);
    std::vector<glm::vec3> pos, nrm;
    Status s = ev.evaluate(joints, root * globals[size_t(node)], tf, pos, nrm);
    INFO(s.error());
    REQUIRE(s.ok());
    for (size_t i = 0; i < pos.size(); ++i) {
      const glm::vec3 p = cpu.mesh.positions[first + i];
      box.add(p);
      const double d = glm::length(pos[i] - p);
      dist.push_back(d);
      const double cosA = glm::dot(glm::normalize(nrm[i]), glm::normalize(cpu.mesh.normals[first + i]));
      if (d < 1e-4) out.maxNormalAngle = std::max(out.maxNormalAngle, std::acos(std::clamp(cosA, -1.0, 1.0)));
      out.gpuPositions.push_back(pos[i]);
    }
    first += mesh.vertexCount();
  }
  REQUIRE(first == cpu.mesh.positions.size());
  std::sort(dist.begin(), dist.end());  // (positions stay in vertex order in gpuPositions)
  out.vertices = dist.size();
  out.maxDistance = dist.back();
  out.diagonal = box.diagonal();
  const FieldProgram prog = standinProgram(a.morph.standin.kind, a.morph.standin.sharpness,
                                           posedOperand(a, timeSec, -1.0).segments);
  for (size_t i = 0; i < out.gpuPositions.size(); ++i)
    if (glm::length(out.gpuPositions[i] - cpu.mesh.positions[i]) > 1e-5 * out.diagonal) {
      ++out.apart;
      out.apartGpuField = std::max(out.apartGpuField, std::abs(test::fieldAt(prog, out.gpuPositions[i])));
      out.apartCpuField = std::max(out.apartCpuField, std::abs(test::fieldAt(prog, cpu.mesh.positions[i])));
    }
  return out;
}

// Checks GPU vs CPU at the progress values of a transition. Re-projection is
// iterative (step-limited Newton, a fallback jump): a float rounding apart can
// send a rare vertex on a ridge of the field to another point of the surface.
// So: every vertex within a micrometre-level bound of the CPU's, except at
// most 1% that are apart but on the posed surface (|f| <= 1e-4), as the CPU's are.
void checkTransition(Context& ctx, TransitionEvaluator& ev, const MorphRuntime& rt, bool expand, const char* what) {
  const MorphMarkers& mk = rt.setup.markers;
  const int f0 = expand ? mk.c : mk.a, f1 = expand ? mk.d : mk.b;
  for (double u : {0.0, 0.5, 0.9, 0.97, 1.0}) {
    const double frame = f0 + u * (f1 - f0);
    const Comparison c = compareWithCpu(ctx, ev, rt, expand, rt.timeline.frameToSec(frame), u);
    INFO(what << " u = " << u << ": " << c.vertices << " vertices (" << c.apart << " apart, |f| there GPU "
              << c.apartGpuField << ", CPU " << c.apartCpuField << "), max " << c.maxDistance << " m, diagonal " << c.diagonal << " m, normals within "
              << c.maxNormalAngle * 57.2958 << " deg");
    CHECK(c.apart <= c.vertices / 100);
    if (c.apart == 0) CHECK(c.maxDistance <= 1e-5 * c.diagonal);
    CHECK(c.apartGpuField <= 1e-4f);
    CHECK(c.maxNormalAngle < 0.01);
  }
}

using DrawRig = test::SceneTarget;

DrawRig makeDrawRig(Context& ctx, uint32_t w, uint32_t h) { return test::makeSceneTarget(ctx, w, h); }

RgbaImage draw(DrawRig& r, const OrbitCamera& cam, const Scene& scene) { return test::renderScene(r, cam, scene); }

size_t countDifferent(const RgbaImage& a, const RgbaImage& b, int tolerance) {
  size_t n = 0;
  for (size_t i = 0; i < a.pixels.size(); i += 4)
    for (int k = 0; k < 3; ++k)
      if (std::abs(int(a.pixels[i + k]) - int(b.pixels[i + k])) > tolerance) {
        ++n;
        break;
      }
  return n;
}

Scene emptyScene() {
  Scene s;
  s.options.grid = false;
  s.options.axisIndicator = false;
  return s;
}

}  // namespace

TEST_CASE("transition shader: positions match the CPU transition on the demo morph", "[gpu][transition]") {
  auto ctx = test::makeTestContext();
  auto ev = TransitionEvaluator::create(*ctx);
  INFO(ev.error());
  REQUIRE(ev.ok());
  const MorphRuntime& rt = *test::demoMorph().runtime;
  checkTransition(*ctx, **ev, rt, false, "creature collapse");
  checkTransition(*ctx, **ev, rt, true, "gear expansion");

  // A painted weight map: alpha per vertex from the easing table and the shift.
  MorphRuntime painted = rt;
  auto& wm = painted.source.morph.weightMap;
  wm.resize(painted.source.vertexCount);
  for (size_t i = 0; i < wm.size(); ++i) wm[i] = float(i % 7) / 6.0f;
  painted.setup.weightMapShift = 0.6f;
  REQUIRE(transitionFrame(painted, false, 0.0, 0.5, true).perVertex);
  checkTransition(*ctx, **ev, painted, false, "creature collapse, painted");
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("transition shader: alpha = 1 lies on the posed stand-in", "[gpu][transition]") {
  auto ctx = test::makeTestContext();
  auto ev = TransitionEvaluator::create(*ctx);
  REQUIRE(ev.ok());
  const MorphRuntime& rt = *test::demoMorph().runtime;
  const double t = rt.timeline.frameToSec(rt.setup.markers.b);
  const Comparison c = compareWithCpu(*ctx, **ev, rt, false, t, 1.0);
  const TransitionFrame tf = transitionFrame(rt, false, t, 1.0, true);
  REQUIRE(tf.reproject);
  const FieldProgram prog = standinProgram(rt.source.morph.standin.kind, rt.source.morph.standin.sharpness, tf.segments);
  size_t on = 0;
  for (const glm::vec3& p : c.gpuPositions) on += std::abs(test::fieldAt(prog, p)) < 1e-4f ? 1 : 0;
  INFO(on << " of " << c.gpuPositions.size() << " vertices with |f| < 1e-4");
  CHECK(double(on) >= 0.99 * double(c.gpuPositions.size()));
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("transition shader: positions match the CPU on tentacle.glb", "[gpu][transition]") {
  const std::string dir = ANIMORPH_SHARED_ASSETS;
  if (!std::filesystem::exists(dir + "/tentacle.glb")) {
    ANIMORPH_SKIP(dir << "/tentacle.glb not present: skipped");
  }
  auto tentacle = importGltf(dir + "/tentacle.glb");
  REQUIRE(tentacle.ok());
  auto made = makeMorphProject(*tentacle, "tentacle.glb", test::demoGear(), "gear.glb");
  INFO(made.error());
  REQUIRE(made.ok());
  // The gear is not next to the asset: only the tentacle's side is prepared.
  Project p = made->project;
  AssetCache assets;
  for (Actor& a : p.actors)
    if (a.assetPath == "gear.glb") a.assetPath = test::demoMorph().dir + "/gear.glb";
  auto rt = prepareMorph(p, dir, assets);
  INFO(rt.error());
  REQUIRE(rt.ok());
  auto ctx = test::makeTestContext();
  auto ev = TransitionEvaluator::create(*ctx);
  REQUIRE(ev.ok());
  checkTransition(*ctx, **ev, **rt, false, "tentacle collapse");
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("transition pipeline: at alpha = 0 it draws exactly what plain skinning draws", "[gpu][transition][render]") {
  auto ctx = test::makeTestContext();
  DrawRig r = makeDrawRig(*ctx, 320, 240);
  const MorphRuntime& rt = *test::demoMorph().runtime;
  const MorphActorRuntime& a = rt.source;
  const Character& c = *a.character;
  const double t = rt.timeline.frameToSec(rt.setup.markers.a) + 0.3;
  const float clipT = a.clip ? float(actorClipTimeSec(a.actor, *a.clip, t)) : 0.0f;
  const auto globals = poseGlobals(c, a.clip, clipT);
  const int node = c.meshNodes().front();
  const auto joints = jointMatrices(c, node, globals);
  auto mesh = GpuMesh::upload(*ctx, c.meshes[size_t(c.nodes[size_t(node)].mesh)]);
  REQUIRE(mesh.ok());
  auto binding = GpuStandinBinding::upload(*ctx, a.binding, a.morph.weightMap);
  REQUIRE(binding.ok());
  OrbitCamera cam;
  const MorphFrame cpuStill = evaluateMorphTransition(rt, t, false, 0.0, {});
  Bounds box;
  for (const glm::vec3& p : cpuStill.mesh.positions) box.add(p);
  cam.frame(box, 320.0f / 240.0f);

  gpu::MeshDraw plain;
  plain.mesh = mesh->get();
  plain.model = a.actor.transform.matrix() * globals[size_t(node)];
  plain.jointMatrices = joints;
  Scene skinned = emptyScene();
  skinned.meshes.push_back(plain);
  const RgbaImage reference = draw(r, cam, skinned);

  const TransitionFrame still = transitionFrame(rt, false, t, 0.0, true);
  REQUIRE(still.uniformAlpha == 0.0f);
  Scene transition = emptyScene();
  transition.transitionMeshes.push_back(TransitionMeshDraw{plain, binding->get(), 0, &still});
  const RgbaImage atZero = draw(r, cam, transition);
  size_t covered = countDifferent(reference, draw(r, cam, emptyScene()), 0);
  INFO(covered << " pixels covered by the mesh");
  CHECK(covered > 2000);
  CHECK(countDifferent(reference, atZero, 0) == 0);
  // The wireframe overlay too: the transition's edges where its vertex shader puts them.
  skinned.options.wireframe = transition.options.wireframe = true;
  skinned.options.wireColor = transition.options.wireColor = {0.0f, 0.0f, 0.0f, 1.0f};
  const RgbaImage wireReference = draw(r, cam, skinned);
  CHECK(countDifferent(wireReference, reference, 0) > 500);
  CHECK(countDifferent(wireReference, draw(r, cam, transition), 0) == 0);
  skinned.options.wireframe = transition.options.wireframe = false;

  // Collapsed (alpha = 1, re-projected): the drawn shape is the CPU transition's.
  const TransitionFrame collapsed = transitionFrame(rt, false, t, 1.0, true);
  transition.transitionMeshes[0].frame = &collapsed;
  const RgbaImage atOne = draw(r, cam, transition);
  const MorphFrame cpu = evaluateMorphTransition(rt, t, false, 1.0, {});
  auto cpuChar = characterFromMesh(cpu.mesh, "cpu");
  auto cpuMesh = GpuMesh::upload(*ctx, cpuChar->meshes[0]);
  REQUIRE(cpuMesh.ok());
  gpu::MeshDraw cpuDraw;
  cpuDraw.mesh = cpuMesh->get();
  Scene cpuScene = emptyScene();
  cpuScene.meshes.push_back(cpuDraw);
  const RgbaImage cpuImage = draw(r, cam, cpuScene);
  const size_t differing = countDifferent(atOne, cpuImage, 8);
  INFO(differing << " pixels differ between the GPU and CPU collapsed shapes");
  CHECK(countDifferent(atOne, reference, 8) > 200);  // the collapse changed the picture
  CHECK(differing < 40);
  // ... in the stand-in's colours (the creature's scales, StandinBinding::standinColors): the
  // shader fades to them as the CPU's vertex colours do (colour within the 8 levels above).
  REQUIRE(a.binding.hasColors());
  REQUIRE(cpu.mesh.colors.size() == cpu.mesh.positions.size());
  auto coloured = [](const RgbaImage& im) {
    size_t n = 0;
    for (size_t i = 0; i < im.pixels.size(); i += 4)
      n += std::abs(int(im.pixels[i]) - int(im.pixels[i + 1])) + std::abs(int(im.pixels[i + 1]) - int(im.pixels[i + 2])) > 24;
    return n;
  };
  INFO(coloured(atOne) << " coloured pixels at alpha 1, " << coloured(reference) << " at alpha 0 (grey: no material bound)");
  CHECK(coloured(reference) == 0);
  CHECK(coloured(atOne) > 1000);
  CHECK(ctx->validationErrorCount() == 0);
}

// A binding without stand-in colours is drawn by the pipelines specialised without the colour
// (AM_SPEC_STANDIN_COLOR false): the same shape, in the material's colour only.
TEST_CASE("transition pipeline: a binding without stand-in colours draws the same shape without the fade",
          "[gpu][transition][render]") {
  auto ctx = test::makeTestContext();
  DrawRig r = makeDrawRig(*ctx, 320, 240);
  const MorphRuntime& rt = *test::demoMorph().runtime;
  const MorphActorRuntime& a = rt.source;
  const Character& c = *a.character;
  REQUIRE(a.binding.hasColors());
  StandinBinding uncolouredBinding = a.binding;
  uncolouredBinding.vertexColors.clear();
  uncolouredBinding.standinColors.clear();
  const double t = rt.timeline.frameToSec(rt.setup.markers.a) + 0.3;
  const float clipT = a.clip ? float(actorClipTimeSec(a.actor, *a.clip, t)) : 0.0f;
  const auto globals = poseGlobals(c, a.clip, clipT);
  const int node = c.meshNodes().front();
  auto mesh = GpuMesh::upload(*ctx, c.meshes[size_t(c.nodes[size_t(node)].mesh)]);
  REQUIRE(mesh.ok());
  auto coloured = GpuStandinBinding::upload(*ctx, a.binding, a.morph.weightMap);
  auto uncoloured = GpuStandinBinding::upload(*ctx, uncolouredBinding, a.morph.weightMap);
  REQUIRE(coloured.ok());
  REQUIRE(uncoloured.ok());
  CHECK((*coloured)->hasColors());
  CHECK_FALSE((*uncoloured)->hasColors());
  const MorphFrame cpuStill = evaluateMorphTransition(rt, t, false, 0.0, {});
  Bounds box;
  for (const glm::vec3& p : cpuStill.mesh.positions) box.add(p);
  OrbitCamera cam;
  cam.frame(box, 320.0f / 240.0f);
  gpu::MeshDraw d;
  d.mesh = mesh->get();
  d.model = a.actor.transform.matrix() * globals[size_t(node)];
  d.jointMatrices = jointMatrices(c, node, globals);
  const RgbaImage background = draw(r, cam, emptyScene());
  auto render = [&](const GpuStandinBinding& b, const TransitionFrame& f) {
    Scene s = emptyScene();
    s.transitionMeshes.push_back(TransitionMeshDraw{d, &b, 0, &f});
    return draw(r, cam, s);
  };
  auto saturated = [](const RgbaImage& im) {
    size_t n = 0;
    for (size_t i = 0; i < im.pixels.size(); i += 4)
      n += std::abs(int(im.pixels[i]) - int(im.pixels[i + 1])) + std::abs(int(im.pixels[i + 1]) - int(im.pixels[i + 2])) > 24;
    return n;
  };
  auto sameCoverage = [&](const RgbaImage& x, const RgbaImage& y) {
    size_t n = 0;
    for (size_t i = 0; i < x.pixels.size(); i += 4) {
      bool cx = false, cy = false;
      for (int k = 0; k < 3; ++k) {
        cx = cx || x.pixels[i + k] != background.pixels[i + k];
        cy = cy || y.pixels[i + k] != background.pixels[i + k];
      }
      n += cx != cy;
    }
    return n;
  };
  // At alpha 0 both variants draw plain skinning: the same image to the bit.
  const TransitionFrame still = transitionFrame(rt, false, t, 0.0, true);
  const RgbaImage stillColoured = render(**coloured, still), stillPlain = render(**uncoloured, still);
  CHECK(countDifferent(stillColoured, background, 0) > 2000);
  CHECK(countDifferent(stillColoured, stillPlain, 0) == 0);
  // Collapsed: the same pixels covered, the coloured variant in the stand-in's colours, the other grey.
  const TransitionFrame collapsed = transitionFrame(rt, false, t, 1.0, true);
  const RgbaImage oneColoured = render(**coloured, collapsed), onePlain = render(**uncoloured, collapsed);
  INFO(saturated(oneColoured) << " coloured pixels with colours, " << saturated(onePlain) << " without");
  CHECK(saturated(oneColoured) > 1000);
  CHECK(saturated(onePlain) == 0);
  CHECK(sameCoverage(oneColoured, onePlain) == 0);
  CHECK(ctx->validationErrorCount() == 0);
}

TEST_CASE("cross-fade: dithered draws at o and 1 - o cover complementary pixels", "[gpu][transition][render]") {
  auto ctx = test::makeTestContext();
  DrawRig r = makeDrawRig(*ctx, 256, 192);
  const Mesh quads = test::twoQuadMesh();
  auto mesh = GpuMesh::upload(*ctx, quads);
  REQUIRE(mesh.ok());
  OrbitCamera cam;
  cam.distanceM = 6.0f;
  std::vector<glm::mat4> joints(6, glm::mat4(1.0f));
  gpu::MeshDraw d;
  d.mesh = mesh->get();
  d.jointMatrices = joints;
  d.doubleSided = true;
  auto sceneWith = [&](std::vector<gpu::MeshDraw> draws) {
    Scene s = emptyScene();
    s.meshes = std::move(draws);
    return s;
  };
  const RgbaImage background = draw(r, cam, emptyScene());
  const RgbaImage full = draw(r, cam, sceneWith({d}));
  gpu::MeshDraw quarter = d, rest = d;
  quarter.opacity = 0.25f;
  rest.opacity = 0.75f;
  rest.complementDither = true;
  const RgbaImage a = draw(r, cam, sceneWith({quarter}));
  const RgbaImage b = draw(r, cam, sceneWith({rest}));
  const RgbaImage both = draw(r, cam, sceneWith({quarter, rest}));
  const size_t fullCount = countDifferent(full, background, 0);
  const size_t aCount = countDifferent(a, background, 0), bCount = countDifferent(b, background, 0);
  INFO(fullCount << " covered, " << aCount << " at 0.25, " << bCount << " at 0.75 (complement)");
  REQUIRE(fullCount > 1000);
  CHECK(std::abs(double(aCount) / double(fullCount) - 0.25) < 0.03);
  CHECK(std::abs(double(bCount) / double(fullCount) - 0.75) < 0.03);
  CHECK(countDifferent(both, full, 0) == 0);  // together: every pixel exactly once, as if opaque
  CHECK(ctx->validationErrorCount() == 0);
}
