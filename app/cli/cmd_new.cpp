// animorph-cli new SOURCE TARGET -o PROJECT.animorph: a complete morph project; each
// side a glTF character, a BlobTree scene or an actor of another project.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/blobtree/blob_tree_json.h"
#include "app/cli/cli_command.h"
#include "app/cli/morph_method_option.h"
#include "core/doc/morph_create.h"
#include "core/project/project_io.h"
#include "core/io/character_import.h"
#include "core/project/new_morph_project.h"

namespace {

using namespace animorph;
namespace fs = std::filesystem;

// path as seen from the project's directory (relative when possible).
std::string relativeTo(const std::string& path, const fs::path& projectDir) {
  std::error_code ec;
  const fs::path abs = fs::absolute(path, ec);
  fs::path rel = fs::relative(abs, projectDir, ec);
  if (ec || rel.empty()) return abs.lexically_normal().string();
  return rel.generic_string();
}

// A character file (glTF, FBX, Collada, OBJ) rather than a BlobTree scene or a project's actor.
bool isCharacter(const std::string& path) { return isCharacterPath(path); }

// One side given on the command line: GLB/glTF, a BlobTree scene (.json) or
// PROJECT.animorph:ACTOR. The actor (glTF paths relative to projectDir) and,
// for a project's glTF actor, the stand-in that project has for it.
struct Side {
  Actor actor;
  std::optional<ActorMorph> morph;
};

Result<Side> readSide(const std::string& arg, const fs::path& projectDir) {
  Side out;
  const size_t colon = arg.rfind(':');
  const size_t dot = arg.rfind(".animorph:");
  if (dot != std::string::npos && colon == dot + 9) {
    const std::string file = arg.substr(0, colon), id = arg.substr(colon + 1);
    auto proj = loadProject(file);
    if (!proj) return Error{proj.error()};
    const Actor* a = proj->findActor(id);
    if (!a) return Error{file + ": no actor with id '" + id + "'"};
    out.actor = *a;
    if (a->kind == ActorKind::Gltf) {
      const fs::path asset(a->assetPath);
      const fs::path abs = asset.is_absolute() ? asset : fs::absolute(fs::path(file)).parent_path() / asset;
      out.actor.assetPath = relativeTo(abs.lexically_normal().string(), projectDir);
      if (const ActorMorph* am = proj->morph.findActor(id)) out.morph = *am;
    }
    return out;
  }
  out.actor.id = fs::path(arg).stem().string();
  if (out.actor.id.empty()) out.actor.id = "actor";
  out.actor.name = out.actor.id;
  if (isCharacter(arg)) {
    out.actor.assetPath = relativeTo(arg, projectDir);
    return out;
  }
  auto tree = loadBlobTreeScene(arg);
  if (!tree) return Error{tree.error()};
  out.actor.kind = ActorKind::BlobTree;
  out.actor.blobTree = std::move(*tree);
  return out;
}

// A side that is not a glTF file: both actors as given, stand-ins fitted for
// the glTF ones that bring none, a BlobTree side without a transition.
int newAnySides(const std::vector<std::string>& inputs, const std::string& output, const NewMorphSettings& s,
                const cli::MorphMethodOptions& methods) {
  std::error_code ec;
  const fs::path dir = fs::absolute(fs::path(output), ec).parent_path();
  Project p;
  for (const std::string& in : inputs) {
    auto side = readSide(in, dir);
    if (!side) return cli::fail("new", side.error());
    side->actor.id = p.uniqueActorId(side->actor.id);
    if (side->morph) {
      side->morph->actorId = side->actor.id;
      p.morph.actors.push_back(*side->morph);
    }
    p.actors.push_back(side->actor);
  }
  p.name = p.actors[0].id + "_to_" + p.actors[1].id;
  p.timeline.fps = s.fps;
  p.timeline.frameStart = 0;
  p.timeline.frameEnd = int(std::lround(s.endSec * s.fps));
  MorphChoice c;
  c.sourceActorId = p.actors[0].id;
  c.targetActorId = p.actors[1].id;
  c.method = s.method;
  c.markers = {int(std::lround(s.aSec * s.fps)), int(std::lround(s.bSec * s.fps)), int(std::lround(s.cSec * s.fps)),
               int(std::lround(s.dSec * s.fps))};
  AssetCache assets;
  std::vector<std::string> notes;
  auto m = proposeMorph(p, dir.string(), assets, c, &notes);
  if (!m) return cli::fail("new", m.error());
  p.morph = std::move(*m);
  cli::applyMorphMethodOptions(methods, p.morph);
  for (const auto& n : notes) std::printf("%s\n", n.c_str());
  for (const Actor& a : p.actors)
    if (a.kind == ActorKind::BlobTree)
      std::printf("%s: a BlobTree: its own tree is the stand-in (no %s)\n", a.id.c_str(),
                  a.id == c.sourceActorId ? "collapse: A = B" : "expansion: C = D");
  if (auto st = saveProject(p, output); !st) return cli::fail("new", st.error());
  const MorphMarkers& k = p.morph.markers;
  std::printf("wrote %s: %s -> %s, markers A %d, B %d, C %d, D %d, frames %d..%d at %g fps, %s\n", output.c_str(),
              c.sourceActorId.c_str(), c.targetActorId.c_str(), k.a, k.b, k.c, k.d, p.timeline.frameStart,
              p.timeline.frameEnd, p.timeline.fps, morphMethodName(p.morph.method));
  return 0;
}

int runNew(const std::vector<std::string>& args) {
  std::vector<std::string> inputs;
  std::string output;
  NewMorphSettings s;
  cli::MorphMethodOptions methods;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-o" || a == "--output") {
      if (i + 1 >= args.size()) return cli::fail("new", a + " needs a value", 2);
      output = args[++i];
    } else if (std::string err; cli::readMorphMethodOption(args, i, methods, err)) {
      if (!err.empty()) return cli::fail("new", err, 2);
    } else if (a == "--allow-rescale") {
      s.allowLargeRescale = true;
    } else if (a == "--accept-poor-fit") {
      s.acceptPoorFit = true;
    } else if (!a.empty() && a[0] == '-') {
      return cli::fail("new", "unknown option " + a, 2);
    } else {
      inputs.push_back(a);
    }
  }
  if (inputs.size() != 2 || output.empty())
    return cli::fail("new", "usage: new SOURCE TARGET -o PROJECT.animorph (see --help)", 2);
  // Skeleton correspondence is the default when both sides have rigs (two glTF characters).
  const bool rigs = isCharacter(inputs[0]) && isCharacter(inputs[1]);
  if (!methods.method) methods.method = rigs ? MorphMethod::SkeletonCorrespondence : MorphMethod::Interpolation;
  s.method = *methods.method;
  if (!rigs) return newAnySides(inputs, output, s, methods);
  auto src = importCharacter(inputs[0]);
  if (!src) return cli::fail("new", src.error());
  auto dst = importCharacter(inputs[1]);
  if (!dst) return cli::fail("new", dst.error());
  std::error_code ec;
  const fs::path dir = fs::absolute(fs::path(output), ec).parent_path();
  auto made = makeMorphProject(*src, relativeTo(inputs[0], dir), *dst, relativeTo(inputs[1], dir), s);
  if (!made)
    return cli::fail("new", made.error() + " (--allow-rescale accepts a large rescale, --accept-poor-fit a poor fit)");
  cli::applyMorphMethodOptions(methods, made->project.morph);
  for (const auto& m : made->messages) std::printf("%s\n", m.c_str());
  for (const auto& w : made->warnings) std::fprintf(stderr, "new: WARNING: %s\n", w.c_str());
  if (auto st = saveProject(made->project, output); !st) return cli::fail("new", st.error());
  const MorphSetup& m = made->project.morph;
  const Timeline& tl = made->project.timeline;
  std::printf("wrote %s: %s -> %s, markers A %d, B %d, C %d, D %d, frames %d..%d at %g fps, %s\n", output.c_str(),
              m.sourceActorId.c_str(), m.targetActorId.c_str(), m.markers.a, m.markers.b, m.markers.c, m.markers.d,
              tl.frameStart, tl.frameEnd, tl.fps, morphMethodName(m.method));
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("new", "a morph project from two characters or BlobTrees (automatic stand-ins, default timeline)",
                     "usage: animorph-cli new SOURCE TARGET -o PROJECT.animorph [--method M]\n"
                     "                        [--correspondence-blend B] [--allow-rescale] [--accept-poor-fit]\n"
                     "  SOURCE, TARGET: a character (.glb, .gltf, .fbx, .dae, .obj), a BlobTree scene (.json) or\n"
                     "  PROJECT.animorph:ACTOR (an actor of another project, with its stand-in).\n"
                     "  A BlobTree side is its own stand-in: no collapse (A = B) or expansion (C = D).\n"
                     "  Writes a complete project: both characters as actors (asset paths relative to\n"
                     "  the project), a stand-in fitted to each, the markers A = 1 s, B = 2 s,\n"
                     "  C = 3.5 s, D = 4.5 s and a timeline of 6 s at 24 fps. When the characters\n"
                     "  differ a lot in size or position, the target is scaled and moved onto the\n"
                     "  source's bounding box and the scale factor applied is printed; files in\n"
                     "  different length units are scaled by their units first (said on a line). A\n"
                     "  further factor over 10x within 2x of a common unit's (cm, mm, inch, foot) in a\n"
                     "  file that declares metres or no unit (glTF holding centimetre numbers) is taken\n"
                     "  as that unit and said so; one that no unit explains is refused unless\n"
                     "  --allow-rescale is given.\n"
                     "  Each stand-in's fit is printed in scene units and % of the diagonal; a poor fit\n"
                     "  (stand-in in more pieces than the mesh, over 10 % of the vertices farther than\n"
                     "  5 % of the diagonal, or a mean over 4 %) is refused, naming the bones, unless\n"
                     "  --accept-poor-fit is given (then it is a warning).\n"
                     "  --method skeleton_correspondence (default with two glTF characters: the\n"
                     "    source's limbs move and resize into the target's along matched skeleton\n"
                     "    chains; `correspond` prints the matching) | interpolation (default with a\n"
                     "    BlobTree side) | space_time\n"
                     "  --correspondence-blend interpolation (default) | space_time: how skeleton\n"
                     "    correspondence combines its two in-between stand-ins\n"
                     "  Exit status: 0 on success, 1 when an input cannot be read or fitted, 2 on bad\n"
                     "  arguments.\n",
                     runNew);
