#pragma once
// Where a bake's frames go (export/bake_route.h), from any worker thread: the per-frame files
// (NAME_####.ply / .obj / .vdb), the animated glTF (fed in frame order: a frame finished early
// waits here until the frames before it are added), and the meshes kept for pictures. Every file
// is staged under a temporary name (StagedFiles) and renamed into place by finish(); a sink
// dropped before that (a failed or cancelled bake) removes its temporaries.
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/export/bake_report.h"
#include "core/export/bake_settings.h"
#include "core/export/frame_files.h"
#include "core/io/gltf_sequence_export.h"
#include "core/poly/level_set_sampler.h"
#include "core/util/result.h"

namespace animorph {

class BakeSink {
 public:
  // Frames first..first+count-1 into o; fps: the glTF's key times (the project's timeline).
  BakeSink(const BakeOutputs& o, int first, int count, double fps);
  BakeSink(const BakeSink&) = delete;
  BakeSink& operator=(const BakeSink&) = delete;

  // Creates the outputs' folders; errors name the folder and the reason.
  Status open() const;
  // Whether a frame's mesh (or its level set) is wanted at all.
  bool wantsMeshes() const;
  bool wantsVolumes() const { return !o_.vdbDir.empty(); }

  // Frame first + k's mesh: its PLY / OBJ staged, the glTF fed, the mesh kept. Errors name the
  // file (by its final name) and the reason.
  Status addMesh(int k, TriangleMesh mesh);
  // Frame first + k's level set; null: the frame has no implicit field (no file).
  Status addVolume(int k, const LevelSetVoxels* band);

  // After every frame: the glTF assembled and staged, every staged file renamed into place; the
  // report's files, level-set counts, glTF figures and kept meshes filled in. Errors: a glTF frame
  // that could not be added (naming it), a --vdb range without any field, a failed write or
  // rename; then no file of this bake is left at the outputs.
  Status finish(BakeReport& report);

 private:
  Status stageWrite(const std::string& finalPath, const std::function<Status(const std::string&)>& write);

  BakeOutputs o_;
  int first_, count_;
  std::mutex stagedMutex_;
  StagedFiles staged_;
  // Per frame (each written by the one thread baking it): the final paths staged.
  std::vector<std::string> plyFiles_, objFiles_, vdbFiles_;
  std::atomic<int> framesWithoutField_{0};
  std::unique_ptr<GltfSequenceWriter> sequence_;
  std::mutex sequenceMutex_;
  std::vector<TriangleMesh> waiting_;  // frames finished before the ones the glTF needs next
  std::vector<char> ready_;
  int nextForGltf_ = 0;
  std::string sequenceError_;
  std::vector<TriangleMesh> kept_;
};

}  // namespace animorph
