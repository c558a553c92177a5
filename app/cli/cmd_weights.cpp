// animorph-cli weights import P.animorph --actor ID (--from red|luminance|alpha | --from-texture alpha|r|g|b)
// [--gltf FILE]: sets a morph actor's weight map from vertex colours or a texture channel and saves the project.
#include <cstdio>
#include <filesystem>

#include "app/cli/cli_command.h"
#include "core/project/project_io.h"
#include "core/io/character_import.h"
#include "core/paint/weights_from_colors.h"
#include "core/paint/weights_from_texture.h"

namespace {

using namespace animorph;
namespace fs = std::filesystem;

int runWeights(const std::vector<std::string>& args) {
  if (args.empty() || args[0] != "import") return cli::fail("weights", "usage: weights import P.animorph --actor ID --from red|luminance|alpha (see --help)", 2);
  std::string project, actorId, from = "red", fromTexture, gltf;
  for (size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= args.size()) return false;
      out = args[++i];
      return true;
    };
    if (a == "--actor") {
      if (!value(actorId)) return cli::fail("weights", "--actor needs a value", 2);
    } else if (a == "--from") {
      if (!value(from)) return cli::fail("weights", "--from needs a value", 2);
    } else if (a == "--from-texture") {
      if (!value(fromTexture)) return cli::fail("weights", "--from-texture needs a value", 2);
    } else if (a == "--gltf") {
      if (!value(gltf)) return cli::fail("weights", "--gltf needs a value", 2);
    } else if (!a.empty() && a[0] == '-') {
      return cli::fail("weights", "unknown option " + a, 2);
    } else if (project.empty()) {
      project = a;
    } else {
      return cli::fail("weights", "only one PROJECT is accepted", 2);
    }
  }
  if (project.empty() || actorId.empty())
    return cli::fail("weights", "usage: weights import P.animorph --actor ID --from red|luminance|alpha", 2);
  auto channel = parseColorChannel(from);
  if (!channel) return cli::fail("weights", "--from: expected red (or color), luminance or alpha, not '" + from + "'", 2);
  auto texChannel = parseTextureChannel(fromTexture);
  if (!fromTexture.empty() && !texChannel)
    return cli::fail("weights", "--from-texture: expected alpha, r, g or b, not '" + fromTexture + "'", 2);

  auto p = loadProject(project);
  if (!p) return cli::fail("weights", p.error());
  const Actor* actor = p->findActor(actorId);
  if (!actor) return cli::fail("weights", project + ": no actor '" + actorId + "'");
  if (actorId != p->morph.sourceActorId && actorId != p->morph.targetActorId)
    return cli::fail("weights", project + ": actor '" + actorId + "' is not the morph's source or target");
  const fs::path base = fs::path(project).parent_path();
  auto resolve = [&](const std::string& path) {
    fs::path q(path);
    return (q.is_absolute() ? q : base / q).lexically_normal().string();
  };
  const std::string actorAsset = resolve(actor->assetPath);
  auto own = importCharacter(actorAsset);
  if (!own) return cli::fail("weights", own.error());
  Character colours;
  if (gltf.empty()) {
    colours = std::move(*own);
  } else {
    auto other = importCharacter(gltf);
    if (!other) return cli::fail("weights", other.error());
    if (other->totalVertices() != own->totalVertices())
      return cli::fail("weights", fs::path(gltf).filename().string() + ": " + std::to_string(other->totalVertices()) +
                                      " vertices, but actor '" + actorId + "' (" + actor->assetPath + ") has " +
                                      std::to_string(own->totalVertices()));
    colours = std::move(*other);
  }
  auto map = texChannel ? weightMapFromTexture(colours, *texChannel) : weightMapFromVertexColors(colours, *channel);
  if (!map) return cli::fail("weights", map.error());
  const std::string source = texChannel ? std::string("texture channel ") + textureChannelName(*texChannel)
                                        : std::string(colorChannelName(*channel));

  ActorMorph* am = p->morph.findActor(actorId);
  if (!am) {
    p->morph.actors.push_back(ActorMorph{});
    am = &p->morph.actors.back();
    am->actorId = actorId;
  }
  am->weightMap = *map;
  if (auto st = saveProject(*p, project); !st) return cli::fail("weights", st.error());
  size_t painted = 0;
  double sum = 0.0;
  for (float w : *map) {
    painted += w > 0.0f;
    sum += w;
  }
  std::printf("%s: weight map of '%s' from the %s of %s: %zu vertices, %zu non-zero, mean %.3f\n", project.c_str(),
              actorId.c_str(), source.c_str(), fs::path(colours.sourcePath).filename().c_str(), map->size(),
              painted, map->empty() ? 0.0 : sum / static_cast<double>(map->size()));
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("weights", "import a morph actor's weight map from vertex colours or a texture channel",
                     "usage: animorph-cli weights import PROJECT.animorph --actor ID\n"
                     "         (--from CHANNEL | --from-texture CHANNEL) [--gltf FILE]\n"
                     "  Sets the weight map of the morph's source or target actor ID (which vertices start\n"
                     "  their transition first) from the vertex colours (COLOR_0) of its file, or from a\n"
                     "  channel of its base colour texture sampled at each vertex's texture coordinates,\n"
                     "  and saves the project in place (atomically).\n"
                     "  --from red | color | luminance | alpha   the vertex colour channel (default red)\n"
                     "  --from-texture alpha | r | g | b         the texture channel (instead of --from)\n"
                     "  --gltf FILE  read the colours from FILE instead of the actor's own asset (same\n"
                     "               vertices in the same order, e.g. a copy painted in another tool)\n"
                     "  Exit status: 0 on success, 1 when a file cannot be read, has no COLOR_0 (no texture) or does not\n"
                     "  match, 2 on bad arguments.\n",
                     runWeights);
