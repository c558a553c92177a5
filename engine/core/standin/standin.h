#pragma once
// A stand-in: the implicit surface a skinned character collapses onto before
// the morph (docs/design.md §4). One primitive per bone, bound to a node of the
// character's rig so the stand-in animates with the skeleton: each segment's
// ends are stored in its node's space and posed by that node's global matrix.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/field/field_program.h"

namespace animorph {

// Convolution segments (Cauchy kernel, summed), or canal surfaces (capsules)
// combined by plain union (max) or blended (sum).
enum class StandinKind : uint8_t { Convolution, CapsuleUnion, CapsuleBlend };

// Every stand-in field uses this threshold: f = p - T. Keeping it common makes
// (1 - w) f1 + w f2 one program with weights scaled (standin_morph/morph_field.h).
inline constexpr float kStandinThreshold = 1.0f;
// Convolution contributions under this fraction of T are cut (field_program.h).
inline constexpr float kStandinCutoffEpsilon = 1e-3f;
// Shortest segment (m): a zero-length convolution segment has no field.
inline constexpr float kMinSegmentLength = 1e-4f;

struct StandinSegment {
  int node = -1;          // character node (a skin joint, or the node of an unskinned mesh)
  glm::vec3 a{0.0f};      // start, in the node's space (metres)
  glm::vec3 b{0.0f};      // end, in the node's space
  float radius = 0.05f;   // surface distance from the segment (metres); weights derive from it
  bool operator==(const StandinSegment&) const = default;
};

struct Standin {
  StandinKind kind = StandinKind::Convolution;
  float sharpness = 20.0f;  // Cauchy kernel S (1/m), convolution only: larger is tighter
  std::vector<StandinSegment> segments;
  bool operator==(const Standin&) const = default;
};

// Colour samples along a segment (docs/morph.md, "Colour"): sample k is the colour (linear RGB)
// of the surface the segment approximates over the k-th of kSegmentColorSamples equal parts of its
// length, from a to b (standin/standin_colors.h samples them from the character's vertices).
inline constexpr int kSegmentColorSamples = 4;
struct SegmentColors {
  std::array<glm::vec3, kSegmentColorSamples> samples{};
  bool set = false;  // false: the segment has no colour of its own (the clay tone)
  // The mean of the samples (the colour of the segment as one primitive).
  glm::vec3 mean() const;
};

// One segment at one time, in the space the caller posed it in.
struct PosedSegment {
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.0f;
  float weightScale = 1.0f;  // multiplies the primitive's weight / intensity (morph, collapse)
  SegmentColors colors{};    // carried along by the morph's in-between stand-ins
};

// The scale a segment's radius takes under matrix m: the mean of its axes' lengths.
float radiusScale(const glm::mat4& m);

// Segment ends in space `root * globals[node]` (globals from rig/pose.h). Segments
// whose node is out of range keep their stored ends under root.
std::vector<PosedSegment> poseStandin(const Standin& s, const std::vector<glm::mat4>& globals, const glm::mat4& root);

// Appends the posed stand-in as one operand of p (potential form) with every
// primitive's weight multiplied by scale * segment.weightScale. Primitives with
// a zero weight are skipped; an empty stand-in pushes a zero constant. Each
// primitive's colour (FieldProgram::classColors) is its segment's mean colour,
// or the program's nextColor for a segment without colours.
void appendStandinOperand(FieldProgram& p, StandinKind kind, float sharpness, const std::vector<PosedSegment>& segs,
                          float scale = 1.0f);

// A finished program for one posed stand-in: f = sum - T (>= 0 inside).
FieldProgram standinProgram(StandinKind kind, float sharpness, const std::vector<PosedSegment>& segs);

// Conservative box around every posed primitive's surface (its radius plus the
// kernel's reach), for polygonisation bounds.
Bounds posedStandinBounds(const std::vector<PosedSegment>& segs, float margin);

// Index of the segment whose surface (capsule of its radius) is closest to x,
// and that surface point; -1 when there are none.
int closestSegmentSurface(const std::vector<PosedSegment>& segs, const glm::vec3& x, glm::vec3& surfacePoint);

const char* standinKindName(StandinKind k);  // "convolution", "capsule_union", "capsule_blend"

}  // namespace animorph
