#pragma once
// One parameter of the generic tree C: p_C = (1 - s) p_A(tA) + s p_B(tB) for
// floats, vectors and control points (lists of different lengths are
// resampled to the longer one), quaternions by shortest-arc slerp; the q of a
// bridged blend / union / hyper-blend pair. Shared by the live evaluation and
// the key-frame bake so both compute the same values.
#include <vector>

#include "core/blobtree/blob_tree.h"

namespace animorph {

// q a blend (1), union (kUnionQ) or hyper-blend (its q track) stands for.
inline constexpr float kUnionQ = 64.0f;
float bridgeQ(const BlobNode& n, double timeSec);

// Point k of a list resampled from `from` to `to` points: lerp(p[i0], p[i1], w).
struct ResampleWeight {
  size_t i0 = 0, i1 = 0;
  float w = 0.0f;
};
std::vector<ResampleWeight> resampleWeights(size_t from, size_t to);

// The blended values themselves, as the write functions below store them (the direct compile of C
// reads them without a snapshot): (1 - s) a(tA) + s b(tB); quaternions by normalised slerp.
float blendFloat(const FloatTrack& a, const FloatTrack& b, double tA, double tB, float s);
glm::vec3 blendVec3(const Vec3Track& a, const Vec3Track& b, double tA, double tB, float s);
glm::quat blendQuat(const QuatTrack& a, const QuatTrack& b, double tA, double tB, float s);
// Control points at t, and the blend of two lists (resampled to the longer one), into out.
void constantPoints(const ControlPoints& p, double timeSec, std::vector<glm::vec3>& out);
void blendPoints(const ControlPoints& a, const ControlPoints& b, double tA, double tB, float s,
                 std::vector<glm::vec3>& out);

// Writes the parameter's value at t into `slot` as a one-key track, reusing
// the slot's memory when it already holds a one-key track of that kind.
void writeConstantParam(ParamValue& slot, const ParamValue& p, double timeSec);
// The same for the blended parameter; a and b hold the same kind.
void writeBlendedParam(ParamValue& slot, const ParamValue& a, const ParamValue& b, double tA, double tB, float s);
// A one-key float track in `slot` holding v (memory reused as above).
void writeConstantFloat(ParamValue& slot, float v);

}  // namespace animorph
