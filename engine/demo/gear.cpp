#include "demo/gear.h"

#include <cmath>

#include "demo/rig_builder.h"

namespace animorph {
namespace {

constexpr int kTeeth = 12;
constexpr int kPerTooth = 16;
constexpr int kSegments = kTeeth * kPerTooth;  // around the axis
constexpr int kSpokes = 4;
constexpr float kHalfThickness = 0.04f;
// Ring radii from the axle hole outwards; the last ring follows the tooth profile.
constexpr float kRings[] = {0.05f, 0.10f, 0.22f, 0.27f};
constexpr int kBands = 4;  // cells between consecutive rings (the outermost band ends at the teeth)
constexpr float kRootRadius = 0.30f, kTipRadius = 0.35f;
constexpr float kHubOuter = 0.10f, kRimInner = 0.22f;

float toothRadius(int segment) {
  // Trapezoid tooth over kPerTooth segments: root, rising flank, tip, falling flank.
  const int k = segment % kPerTooth;
  const float profile[kPerTooth] = {0, 0, 0, 0.25f, 0.6f, 1, 1, 1, 1, 1, 0.6f, 0.25f, 0, 0, 0, 0};
  return kRootRadius + (kTipRadius - kRootRadius) * profile[k];
}

float ringRadius(int ring, int segment) { return ring < kBands ? kRings[ring] : toothRadius(segment); }

// Band 1 (between hub and rim) is open except under the spokes.
bool solidCell(int band, int segment) {
  if (band != 1) return true;
  const int perSpoke = kSegments / kSpokes;
  return segment % perSpoke < perSpoke / 6;
}

glm::vec3 ringPoint(int ring, int segment, float z) {
  const float a = 2.0f * glm::pi<float>() * static_cast<float>(segment % kSegments) / kSegments;
  const float r = ringRadius(ring, segment % kSegments);
  return {r * std::cos(a), r * std::sin(a), z};
}

}  // namespace

Character makeGearCharacter() {
  Mesh mesh;
  mesh.name = "gear";
  auto vertex = [&](const glm::vec3& p, const glm::vec3& n) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
    return static_cast<uint32_t>(mesh.positions.size() - 1);
  };
  // Quad a-b-c-d, counter-clockwise seen from outside, with one flat normal.
  auto quad = [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d) {
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    uint32_t i0 = vertex(a, n), i1 = vertex(b, n), i2 = vertex(c, n), i3 = vertex(d, n);
    mesh.indices.insert(mesh.indices.end(), {i0, i1, i2, i0, i2, i3});
  };
  // Top (+Z) and bottom (-Z) faces share vertices within each face.
  for (float side : {1.0f, -1.0f}) {
    const float z = side * kHalfThickness;
    const glm::vec3 n(0, 0, side);
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (int ring = 0; ring <= kBands; ++ring)
      for (int s = 0; s < kSegments; ++s) vertex(ringPoint(ring, s, z), n);
    auto id = [&](int ring, int s) { return base + ring * kSegments + (s % kSegments); };
    for (int band = 0; band < kBands; ++band)
      for (int s = 0; s < kSegments; ++s) {
        if (!solidCell(band, s)) continue;
        uint32_t a = id(band, s), b = id(band + 1, s), c = id(band + 1, s + 1), d = id(band, s + 1);
        // Radial x angular is counter-clockwise seen from +Z.
        if (side > 0) mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        else mesh.indices.insert(mesh.indices.end(), {a, c, b, a, d, c});
      }
  }
  // Walls along every cell edge between solid and empty (or outside).
  const float zt = kHalfThickness, zb = -kHalfThickness;
  for (int band = 0; band < kBands; ++band)
    for (int s = 0; s < kSegments; ++s) {
      if (!solidCell(band, s)) continue;
      // Inner edge (ring `band`) faces the axis when the band inside is empty.
      if (band == 0 || !solidCell(band - 1, s))
        quad(ringPoint(band, s, zb), ringPoint(band, s, zt), ringPoint(band, s + 1, zt), ringPoint(band, s + 1, zb));
      if (band == kBands - 1 || !solidCell(band + 1, s))
        quad(ringPoint(band + 1, s, zb), ringPoint(band + 1, s + 1, zb), ringPoint(band + 1, s + 1, zt),
             ringPoint(band + 1, s, zt));
      const int prev = (s + kSegments - 1) % kSegments, next = (s + 1) % kSegments;
      if (!solidCell(band, prev))
        quad(ringPoint(band, s, zb), ringPoint(band + 1, s, zb), ringPoint(band + 1, s, zt), ringPoint(band, s, zt));
      if (!solidCell(band, next))
        quad(ringPoint(band, s + 1, zb), ringPoint(band, s + 1, zt), ringPoint(band + 1, s + 1, zt),
             ringPoint(band + 1, s + 1, zb));
    }
  // Hub inside kHubOuter, rim outside kRimInner, linear blend along the spokes.
  for (const auto& p : mesh.positions) {
    const float r = glm::length(glm::vec2(p));
    const float rim = glm::clamp((r - kHubOuter) / (kRimInner - kHubOuter), 0.0f, 1.0f);
    if (rim <= 0.0f) { mesh.joints0.push_back({0, 0, 0, 0}); mesh.weights0.push_back({1, 0, 0, 0}); }
    else if (rim >= 1.0f) { mesh.joints0.push_back({1, 0, 0, 0}); mesh.weights0.push_back({1, 0, 0, 0}); }
    else { mesh.joints0.push_back({0, 1, 0, 0}); mesh.weights0.push_back({1 - rim, rim, 0, 0}); }
  }
  const glm::vec3 centre(0, 0.36f, 0);
  for (auto& p : mesh.positions) p += centre;

  Character c;
  c.sourcePath = "procedural:gear";
  Material bronze;
  bronze.name = "bronze";
  bronze.baseColorFactor = glm::vec4(0.62f, 0.33f, 0.08f, 1.0f);  // linear
  c.materials.push_back(bronze);
  mesh.material = 0;
  c.meshes.push_back(std::move(mesh));
  const int hub = addSkeleton(c, {{"hub", -1, centre, centre + glm::vec3(0, 0, 0.1f)},
                                  {"rim", 0, centre, centre + glm::vec3(0, 0.3f, 0)}},
                              0, "gear_skin");
  AnimationClip turn;
  turn.name = "turn";
  turn.durationSec = 4.0f;
  const glm::vec3 axis(0, 0, 1);
  // Quarter turns per key: slerp between keys 90 degrees apart is exact.
  Channel spin;
  spin.node = hub;
  spin.path = ChannelPath::Rotation;
  spin.interpolation = Interpolation::Linear;
  for (int k = 0; k <= 8; ++k) {
    spin.timesSec.push_back(0.5f * k);
    glm::vec4 q = quatValue(glm::angleAxis(-glm::pi<float>() * 0.25f * k, axis));
    if (!spin.values.empty() && glm::dot(q, spin.values.back()) < 0.0f) q = -q;
    spin.values.push_back(q);
  }
  turn.channels.push_back(spin);
  turn.channels.push_back(sampledChannel(hub + 1, ChannelPath::Rotation, Interpolation::Linear, 4.0f, 16, [&](float t) {
    return quatValue(glm::angleAxis(0.06f * std::sin(2.0f * glm::pi<float>() * t), axis));
  }));
  c.clips.push_back(std::move(turn));
  return c;
}

}  // namespace animorph
