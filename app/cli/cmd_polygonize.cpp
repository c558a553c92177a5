// animorph-cli polygonize: BlobTree scene -> mesh (OBJ, PLY or GLB) on the CPU,
// or with --gpu on the Vulkan compute polygoniser (headless). An explicit --gpu
// that cannot run (no device, a program beyond the GPU's limits, a device
// failure) exits 1 with the reason: no silent fallback to the CPU.
#include <cstdio>
#include <iostream>
#include <thread>

#include "core/animorphosis/evaluate_generic.h"
#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "app/cli/cli_command.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"
#include "core/scene/scene_frame.h"
#include "core/io/mesh_io.h"
#include "core/field/surface_color.h"
#include "core/poly/polygonizer.h"
#include "gpu/vulkan/context.h"
#include "gpu/polygonizer/gpu_polygonizer.h"

namespace {

// Moves a mesh from the tree's space into the world by the actor's transform.
void toWorld(animorph::TriangleMesh& mesh, const glm::mat4& model) {
  if (model == glm::mat4(1.0f)) return;
  const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(model)));
  for (auto& p : mesh.positions) p = glm::vec3(model * glm::vec4(p, 1.0f));
  for (auto& n : mesh.normals) n = glm::normalize(nm * n);
}


bool parseNumber(const std::string& s, double& out) {
  try {
    size_t used = 0;
    out = std::stod(s, &used);
    return used == s.size() && std::isfinite(out);
  } catch (...) {
    return false;
  }
}

using animorph::cli::fail;
constexpr const char* kMe = "polygonize";

struct PolyArgs {
  std::string scene, output, actorId;
  double timeSec = 0.0, res = 128, threads = 0;
  bool cull = true, gpu = false, animorphosis = false;
};

// Reads the options into a; returns 0, or the exit code after printing the reason.
int parsePolyArgs(const std::vector<std::string>& args, PolyArgs& a) {
  const char* me = kMe;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&](double& v) {
      if (i + 1 >= args.size() || !parseNumber(args[i + 1], v)) return false;
      ++i;
      return true;
    };
    if (arg == "--time") {
      if (!value(a.timeSec)) return fail(me, "--time needs a number of seconds", 2);
    } else if (arg == "--res") {
      if (!value(a.res) || a.res < 2 || a.res > 2048 || a.res != std::floor(a.res))
        return fail(me, "--res needs an integer from 2 to 2048", 2);
    } else if (arg == "--threads") {
      if (!value(a.threads) || a.threads < 0) return fail(me, "--threads needs a non-negative integer", 2);
    } else if (arg == "--actor") {
      if (i + 1 >= args.size()) return fail(me, "--actor needs an actor id", 2);
      a.actorId = args[++i];
    } else if (arg == "--animorphosis") {
      a.animorphosis = true;
    } else if (arg == "--no-cull") {
      a.cull = false;
    } else if (arg == "--gpu") {
      a.gpu = true;
    } else if (arg == "-o" || arg == "--output") {
      if (i + 1 >= args.size()) return fail(me, "-o needs an output file (.obj, .ply or .glb)", 2);
      a.output = args[++i];
    } else if (!arg.empty() && arg[0] == '-') {
      return fail(me, "unknown option " + arg, 2);
    } else if (a.scene.empty()) {
      a.scene = arg;
    } else {
      return fail(me, "unexpected argument " + arg, 2);
    }
  }
  if (a.scene.empty()) return fail(me, "missing SCENE (see --help)", 2);
  if (a.output.empty()) return fail(me, "missing -o MESH.{obj,ply,glb}", 2);
  std::string ext = a.output.size() >= 4 ? a.output.substr(a.output.size() - 4) : "";
  if (ext != ".obj" && ext != ".ply" && ext != ".glb")
    return fail(me, a.output + ": unknown mesh format (use .obj, .ply or .glb)", 2);
  return 0;
}

// The tree to polygonise, its time and its placement in the world.
struct PolyTree {
  animorph::Result<animorph::BlobTree> tree = animorph::Error{""};
  double treeTimeSec = 0.0;
  glm::mat4 model{1.0f};
  std::string what;  // the scene (and actor or animorphosis) for messages
};

// The project's BlobTree actor --actor names (or its only one), or the exit code after the reason.
int pickBlobActor(const PolyArgs& a, const animorph::Project& project, const animorph::Actor*& actor) {
  const char* me = kMe;
  std::vector<const animorph::Actor*> blobs;
  for (const auto& act : project.actors)
    if (act.kind == animorph::ActorKind::BlobTree) blobs.push_back(&act);
  if (!a.actorId.empty()) {
    actor = project.findActor(a.actorId);
    if (!actor) return fail(me, a.scene + ": no actor '" + a.actorId + "'");
    if (actor->kind != animorph::ActorKind::BlobTree)
      return fail(me, a.scene + ": actor '" + a.actorId + "' is a glTF character, not a BlobTree");
  } else if (blobs.size() == 1) {
    actor = blobs.front();
  } else {
    std::string ids;
    for (const auto* b : blobs) ids += (ids.empty() ? "" : ", ") + b->id;
    return fail(me, a.scene + ": several BlobTree actors (" + ids + "): choose one with --actor ID", 2);
  }
  return 0;
}

// A project: one of its BlobTree actors (--actor, or the only one), at the actor's tree time for
// scene time --time, in world space; or its animorphosis. Else a scene file (or a project with a
// top-level "blobtree" key). Returns 0, or the exit code after printing the reason.
int loadPolyTree(const PolyArgs& a, PolyTree& t) {
  const char* me = kMe;
  const std::string& scene = a.scene;
  t.treeTimeSec = a.timeSec;
  t.what = scene;
  bool isProject = scene.size() > 9 && scene.substr(scene.size() - 9) == ".animorph";
  auto project = isProject ? animorph::loadProject(scene) : animorph::Result<animorph::Project>(animorph::Error{""});
  if (isProject && !project) return fail(me, project.error());
  bool hasBlobs = false;
  if (isProject)
    for (const auto& act : project->actors) hasBlobs |= act.kind == animorph::ActorKind::BlobTree;
  if (a.animorphosis) {
    // The project's animorphosis C(t): source before its interval, target after it, in the trees' space.
    if (!isProject) return fail(me, "--animorphosis applies to .animorph projects only", 2);
    if (!a.actorId.empty()) return fail(me, "--animorphosis and --actor exclude each other", 2);
    auto c = animorph::projectGenericTree(*project);
    if (!c) return fail(me, scene + ": " + c.error());
    t.tree = animorph::instantiateGeneric(*c, animorph::animorphosisTiming(*project), a.timeSec);
    t.treeTimeSec = 0.0;
    t.what = scene + " animorphosis";
  } else if (isProject && (!a.actorId.empty() || hasBlobs)) {
    const animorph::Actor* actor = nullptr;
    if (int rc = pickBlobActor(a, *project, actor)) return rc;
    t.tree = actor->blobTree;
    t.treeTimeSec = animorph::blobActorTimeSec(*actor, a.timeSec);
    t.model = actor->transform.matrix();
    t.what = scene + " actor '" + actor->id + "'";
  } else {
    if (!a.actorId.empty()) return fail(me, "--actor applies to .animorph projects only", 2);
    t.tree = animorph::loadBlobTreeScene(scene);
    if (!t.tree) return fail(me, t.tree.error());
  }
  return 0;
}

// --gpu: the Vulkan compute polygoniser; no fallback to the CPU.
int polygonizeOnGpu(const PolyArgs& a, const PolyTree& t, const animorph::FieldProgram& program) {
  const char* me = kMe;
  namespace g = animorph::gpu;
  auto field = g::GpuField::single(program);
  if (std::string why = g::GpuPolygonizer::unsupported(field); !why.empty())
    return fail(me, t.what + ": --gpu: the GPU polygoniser cannot evaluate this scene: " + why +
                        " (run without --gpu for the CPU)");
  auto ctx = g::Context::create(g::ContextSettings{});
  if (!ctx) return fail(me, "--gpu: no usable Vulkan device: " + ctx.error() + " (run without --gpu for the CPU)");
  auto poly = g::GpuPolygonizer::create(**ctx);
  if (!poly) return fail(me, "--gpu: " + poly.error());
  g::GpuPolygonizeSettings gs;
  gs.resolution = int(a.res);
  gs.culling = a.cull;
  auto stats = (*poly)->polygonize(field, gs);
  if (!stats) return fail(me, t.what + ": " + stats.error());
  auto mesh = (*poly)->readBack();
  if (!mesh) return fail(me, a.scene + ": " + mesh.error());
  // Vertex colours: the GPU's colour pass (docs/gpu-polygonizer.md, "Colour"). Where it made none (a
  // program without colours: the clay tone; one too long for the device's loop limit), on the CPU
  // from the read-back vertices, by the evaluator the colour pass follows (field/surface_color.h).
  const bool gpuColors = stats->colors && mesh->colors.size() == mesh->positions.size();
  if (!gpuColors) {
    mesh->colors.resize(mesh->positions.size());
    animorph::SurfaceColorEvaluator().evaluate(program, mesh->positions.data(), mesh->positions.size(),
                                               mesh->colors.data());
  }
  toWorld(*mesh, t.model);
  if (auto s = animorph::writeMesh(*mesh, a.output); !s) return fail(me, s.error());
  std::printf("%s at t = %g s: %zu triangles, %zu vertices in %.1f ms (GPU: %s)\n", t.what.c_str(), a.timeSec,
              mesh->triangleCount(), mesh->positions.size(), stats->milliseconds, (*ctx)->deviceName().c_str());
  std::printf("  grid %d x %d x %d (cell %.4g m), %zu primitives, blocks %u evaluated / %u culled of %u -> %s\n",
              stats->gridX, stats->gridY, stats->gridZ, stats->cellSize, program.primitiveCount(),
              stats->blocksActive, stats->blocksTotal - stats->blocksActive, stats->blocksTotal, a.output.c_str());
  std::printf("  colours: %s\n", gpuColors ? "GPU (colour pass)" : "CPU (no GPU colour stream for this program)");
  if ((*ctx)->validationEnabled() && (*ctx)->validationErrorCount() > 0)
    return fail(me, std::to_string((*ctx)->validationErrorCount()) + " Vulkan validation error(s)", 3);
  return 0;
}

int polygonizeOnCpu(const PolyArgs& a, const PolyTree& t, const animorph::FieldProgram& program) {
  const char* me = kMe;
  animorph::PolygonizeSettings settings;
  settings.resolution = int(a.res);
  settings.culling = a.cull;
  settings.threads = int(a.threads);
  settings.colors = true;
  auto result = animorph::polygonize(program, settings);
  if (!result) return fail(me, t.what + ": " + result.error());
  toWorld(result->mesh, t.model);
  if (auto s = animorph::writeMesh(result->mesh, a.output); !s) return fail(me, s.error());
  const auto& st = result->stats;
  std::printf("%s at t = %g s: %zu triangles, %zu vertices in %.1f ms\n", t.what.c_str(), a.timeSec,
              result->mesh.triangleCount(), result->mesh.positions.size(), st.milliseconds);
  std::printf("  grid %d x %d x %d (cell %.4g m), %zu primitives, blocks %zu evaluated / %zu culled of %zu -> %s\n",
              st.gridX, st.gridY, st.gridZ, st.cellSize, program.primitiveCount(), st.blocksEvaluated, st.blocksCulled,
              st.blocksTotal, a.output.c_str());
  std::printf("  %zu field evaluations, %.1f primitives reaching each on average\n", st.pointsEvaluated,
              st.pointsEvaluated ? double(st.primitiveEvaluations) / double(st.pointsEvaluated) : 0.0);
  return 0;
}

int polygonizeCommand(const std::vector<std::string>& args) {
  PolyArgs a;
  if (int rc = parsePolyArgs(args, a)) return rc;
  PolyTree t;
  if (int rc = loadPolyTree(a, t)) return rc;
  animorph::FieldProgram program = animorph::compileFieldProgram(*t.tree, t.treeTimeSec);
  return a.gpu ? polygonizeOnGpu(a, t, program) : polygonizeOnCpu(a, t, program);
}

}  // namespace

ANIMORPH_CLI_COMMAND("polygonize", "polygonise a BlobTree scene at a time into a mesh (CPU, or GPU with --gpu)",
                     "usage: animorph-cli polygonize SCENE --time T --res N [--actor ID | --animorphosis] [--gpu] [--no-cull]\n"
                     "                              [--threads N] -o MESH\n"
                     "  SCENE   a BlobTree scene JSON, or a .animorph project: its BlobTree actor (--actor ID\n"
                     "          when it has several) at scene time T, in world space (the actor's offset,\n"
                     "          speed, loop and transform applied), or its top-level \"blobtree\" key\n"
                     "  --animorphosis  the project's animorphosis at scene time T (source before its\n"
                     "          interval, target after it), in the trees' own space\n"
                     "  --time  seconds (default 0)\n"
                     "  --res   cells along the longest side of the bounds (default 128)\n"
                     "  --no-cull  evaluate every grid corner with every primitive (same mesh, slower)\n"
                     "  --threads  worker threads (default: all)\n"
                     "  --gpu   Vulkan compute polygoniser (offscreen, no display needed), --res up to 512;\n"
                     "          exits 1 with the reason when no device is usable, the scene is beyond the\n"
                     "          GPU's limits or the device fails (no silent fallback to the CPU)\n"
                     "  -o      output mesh: .obj, .ply (binary) or .glb\n"
                     "  Prints the triangle count and the time taken. Errors name the file and the node.\n",
                     polygonizeCommand);
