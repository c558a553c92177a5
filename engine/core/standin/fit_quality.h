#pragma once
// How well a stand-in fits its character (docs/design.md §4), in world units
// (every node transform applied) and relative to the bounding-box diagonal of
// the pose: the mean and largest vertex-to-surface distance, per segment, the
// share of vertices far from the surface, and the connected components of the
// polygonised stand-in against the mesh's -- so that a stand-in in pieces, or
// one that misses a limb, is reported as a poor fit naming its bones.
#include <cstddef>
#include <string>
#include <vector>

#include "core/rig/character.h"
#include "core/standin/character_pose.h"
#include "core/standin/project_onto_standin.h"
#include "core/standin/standin.h"

namespace animorph {

struct FitQualitySettings {
  // A vertex is "far" when its distance to the surface exceeds this fraction of the diagonal.
  double farFraction = 0.05;
  // The fit is poor when more than this share of the vertices is far, when the
  // mean distance exceeds meanFraction of the diagonal, or when the stand-in
  // has more connected components than the mesh. (A box's corners rounded by
  // tubes put about 7 % of its vertices past 5 %: plate.glb is not poor.)
  double poorFarShare = 0.10;
  double poorMeanFraction = 0.04;
  // Polygonise the stand-in (cells along the longest side) to count its
  // components; 0 skips the topology check (components stay -1).
  int topologyResolution = 64;
  // A vertex the projection fails on counts as a miss only when it was left farther than this
  // fraction of the diagonal from the surface: closer, it is stuck in the float noise of the field
  // (|f| about the tolerance), which depends on the rounding of its coordinates and so on the
  // file's unit (quadruped_cm.dae failed on one vertex where quadruped_m.dae did not).
  double surfaceNoiseFraction = 1e-5;
};

// Error of the vertices closest to one segment (world units).
struct SegmentFitError {
  int node = -1;
  std::string bone;        // node name
  float radius = 0.0f;     // posed radius (world units)
  size_t vertices = 0;
  double meanDistance = 0.0;
  double maxDistance = 0.0;
  double farShare = 0.0;   // share of its vertices farther than farFraction * diagonal
};

// The headline figures of a fit, kept from before an automatic repair (standin/repair_fit.h).
struct FitFigures {
  size_t segments = 0;
  double meanDistance = 0.0;    // world units
  double maxDistance = 0.0;
  double farShare = 0.0;
  int standinComponents = -1;
  int meshComponents = -1;
  double largestGap = 0.0;      // world units
  bool poor = false;
};

struct FitReport {
  size_t segments = 0;
  size_t bonesOmitted = 0;      // rig nodes that dominate no vertex
  size_t bonesMerged = 0;       // short or tiny bones fitted into their parent's segment
  size_t helperBridges = 0;     // segments spanning joints without vertices of their own
  double diagonal = 0.0;        // bounding-box diagonal of the fitted pose (world units)
  double meanDistance = 0.0;    // mean vertex distance to the stand-in surface (world units)
  double maxDistance = 0.0;     // largest vertex distance (world units)
  double meanError = 0.0;       // meanDistance / diagonal
  double maxError = 0.0;        // maxDistance / diagonal
  double farShare = 0.0;        // share of vertices farther than farFraction * diagonal
  double farFraction = 0.05;
  int standinComponents = -1;   // of the polygonised stand-in (-1: not measured)
  int meshComponents = -1;      // of the character's mesh, vertices welded by position
  double largestGap = 0.0;      // largest distance from a stand-in piece to the rest (world units; 0: one piece)
  std::vector<SegmentFitError> perSegment;
  std::vector<int> segmentPiece; // polygonised piece nearest each segment's midpoint (empty: not measured)
  int mainPiece = -1;            // the largest piece
  bool poor = false;
  std::vector<std::string> problems;   // one line each, naming bones
  std::vector<std::string> poorBones;  // bones whose segments fit worst or lie in detached pieces
  ProjectionStats projection;   // of the measurement
  size_t projectionMisses = 0;  // projection failures left farther than surfaceNoiseFraction * diagonal
  double milliseconds = 0.0;    // fitting and measuring
  std::vector<std::string> notes;
  // Automatic repair of a poor first fit (standin/repair_fit.h): what was done, one line each
  // naming the bones, and the first fit's figures (beforeRepair is meaningful when repairs is not empty).
  std::vector<std::string> repairs;
  FitFigures beforeRepair;
};

// The headline figures of r.
FitFigures fitFigures(const FitReport& r);

// Measures s against the character at `pose` (standin/character_pose.h, root = identity).
FitReport measureFitQuality(const Character& c, const Standin& s, const CharacterPose& pose,
                            const ProjectionSettings& projection, const FitQualitySettings& settings);

// Connected components of a triangle soup whose vertices are welded by
// position (to weldTolerance): glTF splits vertices at UV and normal seams.
int weldedComponents(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                     float weldTolerance);

// One line: "mean 1.2 (0.8 %), max 9.1 (6.0 %) of a 151 diagonal; 0.3 % of vertices
// farther than 5 %; stand-in 1 piece, mesh 1".
std::string fitSummary(const FitReport& r);

// One line, empty without repairs: "repaired (bridged 'tail3' to 'tail2'; ...): stand-in 2 -> 1
// piece(s), largest gap 0.23 (8.11 %) -> 0; far 10.8 % -> 1.2 %; mean 0.012 (0.9 %) -> 0.009 (0.7 %)".
std::string repairSummary(const FitReport& r);

}  // namespace animorph
