#include "core/standin/standin.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/field/convolution_segment.h"
#include "core/field/skeleton.h"

namespace animorph {

namespace {

// Capsules are skeletal segment primitives g = I (1 - (d / 2R)^2)^2 with
// I = T / 0.75^2: the surface g = T lies exactly at distance R, the support is
// 2R, and scaling I scales the potential (which a morph needs; max and sum of
// scaled potentials stay one Prims op).
constexpr float kCapsuleStiffness = 2.0f;
constexpr float kCapsuleSupport = 2.0f;  // support radius / surface radius

float capsuleIntensity() {
  const float t = 1.0f - 1.0f / (kCapsuleSupport * kCapsuleSupport);
  return kStandinThreshold / (t * t);
}

}  // namespace

const char* standinKindName(StandinKind k) {
  switch (k) {
    case StandinKind::Convolution: return "convolution";
    case StandinKind::CapsuleUnion: return "capsule_union";
    case StandinKind::CapsuleBlend: return "capsule_blend";
  }
  return "convolution";
}

float radiusScale(const glm::mat4& m) {
  return (glm::length(glm::vec3(m[0])) + glm::length(glm::vec3(m[1])) + glm::length(glm::vec3(m[2]))) / 3.0f;
}

std::vector<PosedSegment> poseStandin(const Standin& s, const std::vector<glm::mat4>& globals, const glm::mat4& root) {
  std::vector<PosedSegment> out(s.segments.size());
  for (size_t i = 0; i < s.segments.size(); ++i) {
    const StandinSegment& seg = s.segments[i];
    glm::mat4 m = root;
    if (seg.node >= 0 && seg.node < static_cast<int>(globals.size())) m = root * globals[size_t(seg.node)];
    out[i].a = glm::vec3(m * glm::vec4(seg.a, 1.0f));
    out[i].b = glm::vec3(m * glm::vec4(seg.b, 1.0f));
    // Radii follow the node's scale (mean of the axes' scales).
    out[i].radius = seg.radius * radiusScale(m);
  }
  return out;
}

glm::vec3 SegmentColors::mean() const {
  glm::vec3 m(0.0f);
  for (const glm::vec3& c : samples) m += c;
  return m / float(kSegmentColorSamples);
}

void appendStandinOperand(FieldProgram& p, StandinKind kind, float sharpness, const std::vector<PosedSegment>& segs,
                          float scale) {
  bool pushed = false;
  const float T = p.threshold;
  const glm::vec3 defaultColor = p.nextColor;
  for (const PosedSegment& s : segs) {
    const float w = scale * s.weightScale;
    if (!(w > 0.0f) || !(s.radius >= 0.0f)) continue;
    p.nextColor = s.colors.set ? s.colors.mean() : defaultColor;
    glm::vec3 a = s.a, b = s.b;
    if (glm::length(b - a) < kMinSegmentLength) b = a + glm::vec3(kMinSegmentLength, 0.0f, 0.0f);
    if (kind == StandinKind::Convolution) {
      p.addConvolution(a, b, s.radius, sharpness, kStandinCutoffEpsilon, pushed);
      if (w != 1.0f) {
        // Scale the weight; the cut radius (and the bound) shrink with it.
        ConvolutionData& c = p.convolution;
        const double weight = double(c.weight.back()) * w;
        const double cut = convolutionCutoffRadius(c.length.back(), sharpness, weight, T, kStandinCutoffEpsilon);
        c.weight.back() = float(weight);
        c.cut2.back() = float(cut * cut);
        PrimitiveBound& pb = p.primitiveBounds.back();
        pb.radius = float(cut);
        pb.box = Bounds{};
        pb.box.add(glm::min(a, b) - glm::vec3(float(cut)));
        pb.box.add(glm::max(a, b) + glm::vec3(float(cut)));
      }
    } else {
      SkeletalPrimitive sp;
      sp.skeleton.kind = SkeletonKind::Segment;
      sp.skeleton.p0 = a;
      sp.skeleton.p1 = b;
      sp.radius = kCapsuleSupport * std::max(s.radius, 1e-6f);
      sp.intensity = capsuleIntensity() * (T / kStandinThreshold) * w;
      sp.stiffness = kCapsuleStiffness;
      p.addSkeletal(sp, pushed, kind == StandinKind::CapsuleUnion);
    }
    pushed = true;
  }
  p.nextColor = defaultColor;
  if (!pushed) p.addConstant(0.0f);
}

FieldProgram standinProgram(StandinKind kind, float sharpness, const std::vector<PosedSegment>& segs) {
  FieldProgram p;
  p.threshold = kStandinThreshold;
  appendStandinOperand(p, kind, sharpness, segs, 1.0f);
  p.finish();
  return p;
}

Bounds posedStandinBounds(const std::vector<PosedSegment>& segs, float margin) {
  Bounds b;
  for (const PosedSegment& s : segs) {
    if (!(s.weightScale > 0.0f)) continue;
    const float r = 1.5f * s.radius + margin;
    b.add(glm::min(s.a, s.b) - glm::vec3(r));
    b.add(glm::max(s.a, s.b) + glm::vec3(r));
  }
  return b;
}

int closestSegmentSurface(const std::vector<PosedSegment>& segs, const glm::vec3& x, glm::vec3& surfacePoint) {
  int best = -1;
  float bestD = std::numeric_limits<float>::max();
  for (size_t i = 0; i < segs.size(); ++i) {
    const PosedSegment& s = segs[i];
    glm::vec3 c = closestOnSegment(x, s.a, s.b);
    float d = std::abs(glm::length(x - c) - s.radius);
    if (d < bestD) {
      bestD = d;
      best = int(i);
      glm::vec3 dir = x - c;
      float len = glm::length(dir);
      if (len < 1e-9f) {
        // On the axis: any direction perpendicular to it.
        glm::vec3 ax = s.b - s.a;
        dir = glm::cross(ax, std::abs(ax.x) < 0.9f * glm::length(ax) ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
        len = glm::length(dir);
        if (len < 1e-12f) { dir = glm::vec3(0, 1, 0); len = 1.0f; }
      }
      surfacePoint = c + dir / len * s.radius;
    }
  }
  return best;
}

}  // namespace animorph
