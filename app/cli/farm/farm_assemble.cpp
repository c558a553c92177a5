// animorph-cli farm assemble: the animated glTF chunks written by a farm's bake tasks, read back
// and joined into one glTF of the whole range (and/or rendered into one playblast) (cli/farm.h).
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/export/frame_chunks.h"
#include "core/export/frame_files.h"
#include "app/cli/cli_command.h"
#include "app/cli/farm/farm.h"
#include "app/cli/playblast.h"
#include "core/project/project_io.h"
#include "core/io/gltf_sequence_export.h"
#include "core/io/gltf_sequence_import.h"

namespace animorph::cli {

int runFarmAssemble(const FarmOptions& o) {
  namespace fs = std::filesystem;
  if (o.chunksDir.empty()) return fail("farm", "assemble: --chunks DIR is needed (where the chunks' glTFs are)", 2);
  if (o.gltf.empty() && o.mp4.empty()) return fail("farm", "assemble: nothing to write: give --gltf and/or --mp4", 2);
  auto p = loadProject(o.project);
  if (!p) return fail("farm", p.error());
  const std::string name = o.name.empty() ? framePrefix(p->name) : o.name;
  const auto t0 = std::chrono::steady_clock::now();
  GltfSequenceOptions so;
  so.name = name;
  so.fps = p->timeline.fps;
  so.firstFrame = o.first;
  GltfSequenceWriter sequence(so);
  std::vector<TriangleMesh> kept;  // for --mp4
  const std::vector<FrameChunk> chunks = splitFrames(o.first, o.last, o.chunkFrames);
  for (const FrameChunk& c : chunks) {
    const std::string path = chunkGltfName(o.chunksDir, name, c);
    auto frames = readGltfSequence(path, name);
    if (!frames) return fail("farm", "assemble: " + frames.error());
    const int n = c.last - c.first + 1;
    if (int(frames->size()) != n || frames->front().frame != c.first || frames->back().frame != c.last)
      return fail("farm", "assemble: " + path + ": holds " + std::to_string(frames->size()) + " frames " +
                              std::to_string(frames->front().frame) + ".." + std::to_string(frames->back().frame) +
                              ", expected the " + std::to_string(n) + " frames " + std::to_string(c.first) + ".." +
                              std::to_string(c.last));
    for (SequenceFrame& f : *frames) {
      if (Status st = sequence.addFrame(f.mesh); !st) return fail("farm", "assemble: " + path + ": " + st.error());
      if (!o.mp4.empty()) kept.push_back(std::move(f.mesh));
    }
  }
  const double readSec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::error_code ec;
  if (!o.gltf.empty()) {
    if (fs::path(o.gltf).has_parent_path()) fs::create_directories(fs::path(o.gltf).parent_path(), ec);
    if (ec) return fail("farm", "assemble: " + o.gltf + ": cannot create its directory: " + ec.message());
    const int meshes = sequence.meshCount();
    if (Status st = writeGltfSequence(sequence, o.gltf); !st) return fail("farm", "assemble: " + st.error());
    std::printf("assembled frames %d..%d from %zu chunks in %s into %s: %d distinct meshes, %.1f MB, in %.2f s\n",
                o.first, o.last, chunks.size(), o.chunksDir.c_str(), o.gltf.c_str(), meshes,
                double(fs::file_size(o.gltf, ec)) / 1e6,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  if (!o.mp4.empty()) {
    PictureOptions pics;
    pics.mp4 = o.mp4;
    pics.burnIn = o.burnIn;
    pics.stages = frameStageSpans(*p, o.first, o.last);
    pics.fps = p->timeline.fps;
    std::sscanf(o.size.c_str(), "%ux%u", &pics.width, &pics.height);
    if (fs::path(o.mp4).has_parent_path()) fs::create_directories(fs::path(o.mp4).parent_path(), ec);
    if (ec) return fail("farm", "assemble: " + o.mp4 + ": cannot create its directory: " + ec.message());
    std::printf("read %zu frames from %zu chunks in %.2f s\n", kept.size(), chunks.size(), readSec);
    if (int code = renderPictures(kept, o.first, fs::path(), name, p->view, pics); code != 0) return code;
  }
  if (o.keepChunks) return 0;
  // Everything is written: the chunks go (a long bake's chunks would fill the farm's disk).
  size_t removed = 0;
  for (const FrameChunk& c : chunks) removed += fs::remove(chunkGltfName(o.chunksDir, name, c), ec) ? 1 : 0;
  fs::remove(o.chunksDir, ec);  // only when nothing else is in it
  std::printf("removed the %zu chunk glTFs from %s (--keep-chunks keeps them)\n", removed, o.chunksDir.c_str());
  return 0;
}

}  // namespace animorph::cli
