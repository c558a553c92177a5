// libFuzzer target: importGltf on one file (ANIMORPH_FUZZ_FILE_NAME: "input.gltf" for
// the JSON target, "input.glb" for the binary one). The input is written into a private
// directory beside a small external buffer "mesh.bin" (so URIs that name it resolve);
// an imported character is then posed and skinned at a few times of each clip, as the
// editor does when it plays one.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fuzz_check.h"
#include "core/io/gltf_import.h"
#include "core/rig/skinning.h"

namespace {

namespace fs = std::filesystem;

const fs::path& workDir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("animorph-fuzz-gltf-" + std::to_string(::getpid()));
    fs::create_directories(d);
    // 36 bytes: three float VEC3s, the size the seeds' external buffer declares.
    const float bin[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    if (FILE* f = std::fopen((d / "mesh.bin").c_str(), "wb")) {
      std::fwrite(bin, sizeof bin, 1, f);
      std::fclose(f);
    }
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

  auto ch = importGltf(path);
  if (!fuzz::loaded(ch, path)) return 0;
  const size_t vertices = ch->totalVertices();
  fuzz::require(skinnedWorldPositions(*ch, nullptr, 0.0f).size() == vertices, "rest pose has every vertex");
  for (const AnimationClip& clip : ch->clips)
    for (float t : {-1.0f, 0.0f, 0.5f * clip.durationSec, clip.durationSec, clip.durationSec + 1.0f})
      fuzz::require(skinnedWorldPositions(*ch, &clip, t).size() == vertices, "posed clip has every vertex");
  return 0;
}
