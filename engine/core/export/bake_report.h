#pragma once
// What a bake did (export/bake_route.h): the frames, the triangles per stage, the files written,
// the temporal coherence's reuse, the continuity measures, and the meshes when they were kept.
// animorph-cli bake prints it; File > Export... and the playblast take what they show from it.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/export/bake_continuity.h"
#include "core/poly/mesh.h"

namespace animorph {

// An animorphosis baked on one grid with temporal coherence.
struct BakeCoherence {
  float toleranceCells = 0.0f;  // BakeSettings::coherence
  size_t blocksEvaluated = 0;   // over all frames (reused blocks count here too)
  size_t blocksReused = 0;
  std::array<int, 3> gridCells{};  // the one grid every frame was polygonised on
};

struct BakeReport {
  int first = 0, last = 0, frames = 0;  // the scene frames baked
  bool animorphosis = false;            // the frames were an animorphosis' C(t) (else a morph's)
  size_t animorphosisNodes = 0;         // the nodes of C
  // Per MorphStage (source, collapse, morph, expand, target): frames and their triangles. An
  // animorphosis' frames count as morph. Triangles are counted when meshes were made.
  std::array<int, 5> stageFrames{};
  std::array<size_t, 5> stageTriangles{};
  size_t triangles = 0;  // over all frames
  // The files written, in frame order (PLY, OBJ, VDB of each frame), the .glb last.
  std::vector<std::string> files;
  int levelSets = 0;           // .vdb files written
  int framesWithoutField = 0;  // --vdb: skinned-mesh frames, which have no level set
  int gltfMeshes = 0;          // distinct meshes in the .glb (repeated frames share one)
  double gltfMegabytes = 0.0;  // the .glb's size
  double gltfSeconds = 0.0;    // assembling and writing it
  std::optional<BakeCoherence> coherence;   // an animorphosis baked with coherence > 0
  std::optional<BakeContinuity> continuity; // a morph with BakeSettings::measureContinuity
  std::vector<TriangleMesh> meshes;         // with BakeOutputs::keepMeshes: frame first + k at k
  double frameSeconds = 0.0;  // baking the frames (without writing the .glb and renaming)
  double seconds = 0.0;       // the whole bake
};

}  // namespace animorph
