// libFuzzer target: importCharacter on one FBX or Collada file (ANIMORPH_FUZZ_FILE_NAME:
// "input.fbx" for fuzz_fbx, "input.dae" for fuzz_collada), which goes through assimp
// (io/assimp_import.h) after the declared-size checks and the readers that run beside assimp
// (io/fbx_shape_values: the blend shape channels' values; io/collada_morphs: <morph> controllers
// and the document rewritten for assimp). The input is written into a private
// directory; an imported character is then posed and skinned at a few times of each clip, as
// the editor does when it plays one, and its weights must sum to 1.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fuzz_check.h"
#include "core/io/character_import.h"
#include "core/rig/skinning.h"

namespace {

namespace fs = std::filesystem;

const fs::path& workDir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("animorph-fuzz-assimp-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace animorph;
  const std::string path = (workDir() / ANIMORPH_FUZZ_FILE_NAME).string();
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  const bool written = std::fwrite(data, 1, size, f) == size;
  std::fclose(f);
  if (!written) return 0;

  auto ch = importCharacter(path);
  if (!fuzz::loaded(ch, path)) return 0;
  const size_t vertices = ch->totalVertices();
  for (const Mesh& m : ch->meshes)
    for (size_t v = 0; v < m.weights0.size(); ++v) {
      float sum = m.weights0[v].x + m.weights0[v].y + m.weights0[v].z + m.weights0[v].w;
      if (!m.weights1.empty()) sum += m.weights1[v].x + m.weights1[v].y + m.weights1[v].z + m.weights1[v].w;
      fuzz::require(std::abs(sum - 1.0f) < 1e-3f, "skin weights sum to 1");
    }
  fuzz::require(skinnedWorldPositions(*ch, nullptr, 0.0f).size() == vertices, "rest pose has every vertex");
  for (const AnimationClip& clip : ch->clips)
    for (float t : {-1.0f, 0.0f, 0.5f * clip.durationSec, clip.durationSec, clip.durationSec + 1.0f})
      fuzz::require(skinnedWorldPositions(*ch, &clip, t).size() == vertices, "posed clip has every vertex");
  return 0;
}
