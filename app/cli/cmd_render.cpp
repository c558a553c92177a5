// animorph-cli render: the viewport of a project, rendered offscreen to PNG.
#include <cstdio>
#include <cstdlib>

#include "app/cli/cli_command.h"
#include "gpu/vulkan/context.h"
#include "core/doc/document.h"
#include "gpu/render/mesh_cache.h"
#include "gpu/present/offscreen_target.h"
#include "core/blobtree/compile.h"
#include "core/poly/polygonizer.h"
#include "core/scene/animorphosis_scene.h"
#include "core/scene/mesh_character.h"
#include "core/scene/morph_scene.h"
#include "core/scene/scene_frame.h"
#include "gpu/frame/scene_from_frame.h"
#include "gpu/render/scene_renderer.h"
#include "core/camera/camera.h"

namespace {

using namespace animorph;

int runRender(const std::vector<std::string>& args) {
  std::string project, output;
  int frameNo = -1, width = 1280, height = 720;
  float yawDeg = 35.0f, pitchDeg = 20.0f;
  int morphResolution = 64;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw std::runtime_error(a + " needs a value");
      return args[++i];
    };
    if (a == "--frame") frameNo = std::atoi(value().c_str());
    else if (a == "--size") {
      if (std::sscanf(value().c_str(), "%dx%d", &width, &height) != 2 || width < 1 || height < 1 || width > 8192 ||
          height > 8192)
        return cli::fail("render", "--size expects WxH between 1x1 and 8192x8192", 2);
    } else if (a == "-o" || a == "--output") output = value();
    else if (a == "--yaw") yawDeg = std::strtof(value().c_str(), nullptr);
    else if (a == "--pitch") pitchDeg = std::strtof(value().c_str(), nullptr);
    else if (a == "--res") morphResolution = std::atoi(value().c_str());
    else if (!a.empty() && a[0] == '-') return cli::fail("render", "unknown option " + a, 2);
    else project = a;
  }
  if (project.empty() || output.empty()) return cli::fail("render", "usage: render PROJECT -o FILE.png (see --help)", 2);

  auto docR = Document::open(project);
  if (!docR) return cli::fail("render", docR.error());
  Document& doc = **docR;
  const Timeline& tl = doc.project().timeline;
  if (frameNo < 0) frameNo = tl.currentFrame;

  AssetCache assets;
  const double timeSec = tl.frameToSec(frameNo);
  SceneFrame frame = evaluateScene(doc.project(), doc.baseDir(), assets, timeSec);
  for (const auto& e : frame.errors) std::fprintf(stderr, "animorph-cli render: warning: %s\n", e.c_str());
  std::string stage;
  MorphCache morphCache;
  if (auto rt = morphCache.get(doc.project(), doc.baseDir(), assets, &doc, doc.revision())) {
    MorphFrameSettings ms;
    ms.resolution = morphResolution;
    MorphSceneInfo info = applyMorph(frame, *rt, timeSec, ms);
    if (!info.error.empty()) return cli::fail("render", "morph: " + info.error);
    stage = ", morph stage " + describeMorphStage(info);
  } else if (!morphCache.error().empty()) {
    std::fprintf(stderr, "animorph-cli render: warning: morph: %s\n", morphCache.error().c_str());
  }
  // BlobTree actors (and an animorphosis' C(t) in their place): polygonised on the CPU at --res and
  // drawn as meshes placed by the actor's transform (the editor's preview does the same on a worker).
  AnimorphosisCache animorphosisCache;
  AnimorphosisSceneInfo ai = applyAnimorphosis(frame, doc.project(), animorphosisCache, &doc, doc.revision());
  if (ai.stage != AnimorphosisStage::None) stage += ", " + describeAnimorphosis(ai);
  for (const BlobDraw& b : frame.blobs) {
    const Actor* actor = doc.project().findActor(b.actorId);
    const std::shared_ptr<const BlobTree> own = b.ownTree();
    if (!own && !actor) continue;
    PolygonizeSettings ps;
    ps.resolution = morphResolution;
    ps.colors = !b.tint;  // as the editor draws it: in the primitives' colours, a ghost in its tint
    auto poly = polygonize(compileFieldProgram(own ? *own : actor->blobTree, b.treeTimeSec), ps);
    if (!poly) return cli::fail("render", "BlobTree actor '" + b.actorId + "': " + poly.error());
    MeshDraw d;
    d.actorId = b.actorId;
    d.character = characterFromMesh(poly->mesh, b.actorId);
    d.meshNode = 0;
    d.meshIndex = 0;
    d.joints = {b.model};
    if (b.tint) d.color = *b.tint;
    frame.meshes.push_back(std::move(d));
  }

  gpu::ContextSettings cs;
  auto ctxR = gpu::Context::create(cs);
  if (!ctxR) return cli::fail("render", "no usable Vulkan device: " + ctxR.error());
  gpu::Context& ctx = **ctxR;
  int code = 0;
  {
    auto target = gpu::OffscreenTarget::create(ctx, static_cast<uint32_t>(width), static_cast<uint32_t>(height));
    if (!target) return cli::fail("render", target.error());
    auto renderer = gpu::SceneRenderer::create(ctx, (*target)->renderPass());
    if (!renderer) return cli::fail("render", renderer.error());
    gpu::MeshCache meshes(ctx);
    gpu::Scene scene;
    gpu::buildScene(frame, doc.project().view, {}, meshes, scene);
    if (!meshes.lastError().empty()) std::fprintf(stderr, "animorph-cli render: warning: %s\n", meshes.lastError().c_str());

    OrbitCamera cam;
    cam.yawRad = glm::radians(yawDeg);
    cam.pitchRad = glm::radians(pitchDeg);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    cam.frame(posedBounds(frame), aspect);
    gpu::ViewportRect rect{0, 0, static_cast<uint32_t>(width), static_cast<uint32_t>(height)};
    Status recorded = Status::success();
    Status st = (*target)->render([&](VkCommandBuffer cmd) { recorded = (*renderer)->record(cmd, (*target)->serial(), rect, cam, scene); },
                                  scene.options.background);
    if (!st) return cli::fail("render", st.error());
    if (!recorded) return cli::fail("render", recorded.error());
    Status w = gpu::writePng(output, (*target)->image());
    if (!w) return cli::fail("render", w.error());
    std::printf("wrote %s (%dx%d, frame %d, %zu meshes%s, device %s)\n", output.c_str(), width, height, frameNo,
                scene.meshes.size(), stage.c_str(), ctx.deviceName().c_str());
  }
  if (ctx.validationEnabled() && ctx.validationErrorCount() > 0) {
    std::fprintf(stderr, "animorph-cli render: %u Vulkan validation error(s)\n", ctx.validationErrorCount());
    code = 3;
  }
  return code;
}

}  // namespace

ANIMORPH_CLI_COMMAND("render", "render a project's viewport offscreen to PNG (no window, no X server)",
                     "usage: animorph-cli render PROJECT.animorph -o FILE.png [--frame N] [--size WxH]\n"
                     "                           [--yaw DEG] [--pitch DEG] [--res N]\n"
                     "  Renders the scene at frame N (default: the project's current frame) with the\n"
                     "  project's view options, the camera framing every actor. Uses the Vulkan device\n"
                     "  chosen as in the editor (ANIMORPH_GPU overrides). In a project with a morph,\n"
                     "  the frame shows the morph's stage; BlobTree actors (and an animorphosis' C(t))\n"
                     "  are polygonised on the CPU at --res; --res is the polygonisation resolution of\n"
                     "  the implicit stage (default 64).\n",
                     runRender);
