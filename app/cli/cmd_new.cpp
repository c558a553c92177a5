// animorph-cli new SOURCE.glb TARGET.glb -o PROJECT.animorph: a complete morph project.
#include <cstdio>
#include <filesystem>

#include "cli/cli_command.h"
#include "doc/project_io.h"
#include "io/gltf_import.h"
#include "morph/new_morph_project.h"

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

int runNew(const std::vector<std::string>& args) {
  std::vector<std::string> inputs;
  std::string output;
  NewMorphSettings s;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-o" || a == "--output") {
      if (i + 1 >= args.size()) return cli::fail("new", a + " needs a value", 2);
      output = args[++i];
    } else if (a == "--method") {
      if (i + 1 >= args.size()) return cli::fail("new", "--method needs a value", 2);
      const std::string v = args[++i];
      if (v == "interpolation") s.method = MorphMethod::Interpolation;
      else if (v == "space_time") s.method = MorphMethod::SpaceTime;
      else return cli::fail("new", "--method: expected interpolation or space_time", 2);
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
    return cli::fail("new", "usage: new SOURCE.glb TARGET.glb -o PROJECT.animorph (see --help)", 2);
  auto src = importGltf(inputs[0]);
  if (!src) return cli::fail("new", src.error());
  auto dst = importGltf(inputs[1]);
  if (!dst) return cli::fail("new", dst.error());
  std::error_code ec;
  const fs::path dir = fs::absolute(fs::path(output), ec).parent_path();
  auto made = makeMorphProject(*src, relativeTo(inputs[0], dir), *dst, relativeTo(inputs[1], dir), s);
  if (!made)
    return cli::fail("new", made.error() + " (--allow-rescale accepts a large rescale, --accept-poor-fit a poor fit)");
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

ANIMORPH_CLI_COMMAND("new", "a morph project from two glTF characters (automatic stand-ins, default timeline)",
                     "usage: animorph-cli new SOURCE.glb TARGET.glb -o PROJECT.animorph [--method M]\n"
                     "                        [--allow-rescale] [--accept-poor-fit]\n"
                     "  Writes a complete project: both characters as actors (asset paths relative to\n"
                     "  the project), a stand-in fitted to each, the markers A = 1 s, B = 2 s,\n"
                     "  C = 3.5 s, D = 4.5 s and a timeline of 6 s at 24 fps. When the characters\n"
                     "  differ a lot in size or position, the target is scaled and moved onto the\n"
                     "  source's bounding box and the scale factor applied is printed; a factor over\n"
                     "  10x (files in different units?) is refused unless --allow-rescale is given.\n"
                     "  Each stand-in's fit is printed in scene units and % of the diagonal; a poor fit\n"
                     "  (stand-in in more pieces than the mesh, over 10 % of the vertices farther than\n"
                     "  5 % of the diagonal, or a mean over 4 %) is refused, naming the bones, unless\n"
                     "  --accept-poor-fit is given (then it is a warning).\n"
                     "  --method interpolation (default) | space_time\n"
                     "  Exit status: 0 on success, 1 when an input cannot be read or fitted, 2 on bad\n"
                     "  arguments.\n",
                     runNew);
