#pragma once
// Popping between consecutive frames (docs/morph.md, "Continuity"): what a
// viewer sees as a pop is a frame whose shape jumps from its neighbour's. Per
// frame the mesh's enclosed volume; an empty frame, or one whose volume
// changes by more than a stated fraction from the frame before, is a defect
// (animorph-cli bake reports them); the largest frame-to-frame change of
// volume and of Hausdorff distance make popping measurable (bench
// morph-continuity compares them with the characters' own motion).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/poly/mesh.h"

namespace animorph {

// A frame whose volume differs from the previous frame's by more than this
// fraction (of the larger of the two) is reported.
inline constexpr double kMaxFrameVolumeChange = 0.2;

struct FrameMeasure {
  int frame = 0;
  size_t triangles = 0;
  double volume = 0.0;     // m^3 (divergence theorem; with a stand-in core, the union's)
  double hausdorff = 0.0;  // m, to the previous frame's mesh (0 for the first, or when not measured)
};

// |b - a| / max(|a|, |b|); 0 when both are 0.
double relativeVolumeChange(double a, double b);

// Symmetric Hausdorff distance between the meshes, over their vertices to the
// other's triangles; infinite when one is empty and the other not, 0 when both are.
double hausdorffDistance(const TriangleMesh& a, const TriangleMesh& b);

// coreTriangles > 0: the mesh's last coreTriangles triangles are the stand-in
// core (MorphFrame::coreTriangles), a shell overlapping the rest; the volume is
// then the union's (poly/union_volume.h), not the sum.
FrameMeasure measureFrame(int frame, const TriangleMesh& mesh, const TriangleMesh* previous,
                          size_t coreTriangles = 0);

struct ContinuityDefect {
  int frame = 0;
  std::string reason;  // "empty", "volume -49% from frame 84"
};

// Empty frames, and frames whose volume changes by more than maxChange from the previous frame.
std::vector<ContinuityDefect> continuityDefects(const std::vector<FrameMeasure>& frames,
                                                double maxChange = kMaxFrameVolumeChange);

struct ContinuitySummary {
  std::vector<FrameMeasure> frames;
  double maxVolumeChange = 0.0;  // largest relativeVolumeChange between consecutive frames
  int maxVolumeFrame = 0;        // the later frame of that pair
  double maxHausdorff = 0.0;     // largest Hausdorff distance between consecutive frames (m)
  int maxHausdorffFrame = 0;
  size_t emptyFrames = 0;
};

// A frame's mesh and how many of its last triangles are the stand-in core.
struct FrameShape {
  FrameShape(TriangleMesh m = {}, size_t core = 0) : mesh(std::move(m)), coreTriangles(core) {}  // NOLINT
  TriangleMesh mesh;
  size_t coreTriangles = 0;
};

// Measures frames first..last, shapeOf(frame) giving each frame's mesh (in order, one at a time).
ContinuitySummary measureContinuity(int first, int last, const std::function<FrameShape(int)>& shapeOf,
                                    bool hausdorff = true);

}  // namespace animorph
