#include "demo/dense.h"

#include <algorithm>
#include <cmath>

#include "demo/rig_builder.h"

namespace animorph {

Character makeDenseCharacter(size_t targetTriangles) {
  constexpr int kBones = 8;
  constexpr float kLength = 2.0f, kRadius = 0.1f;
  const int around = targetTriangles >= 20000 ? 128 : 32;
  // 2 * around triangles per ring gap plus 2 * around for the caps.
  const int rings = std::max(2, static_cast<int>(targetTriangles / (2 * around)));
  Mesh mesh;
  mesh.name = "dense_tube";
  for (int r = 0; r < rings; ++r) {
    const float x = kLength * r / (rings - 1);
    for (int a = 0; a < around; ++a) {
      const float ang = 2.0f * glm::pi<float>() * a / around;
      const glm::vec3 n(0, std::cos(ang), std::sin(ang));
      mesh.positions.push_back(glm::vec3(x, 0, 0) + kRadius * n);
      mesh.normals.push_back(n);
    }
  }
  for (int r = 0; r + 1 < rings; ++r)
    for (int a = 0; a < around; ++a) {
      const uint32_t i0 = r * around + a, i1 = r * around + (a + 1) % around;
      const uint32_t j0 = i0 + around, j1 = i1 + around;
      mesh.indices.insert(mesh.indices.end(), {i0, i1, j1, i0, j1, j0});
    }
  // Caps: a centre vertex fanned to each end ring.
  for (int end = 0; end < 2; ++end) {
    const float x = end ? kLength : 0.0f;
    const uint32_t centre = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back({x, 0, 0});
    mesh.normals.push_back({end ? 1.0f : -1.0f, 0, 0});
    const uint32_t ring = end ? (rings - 1) * around : 0;
    for (int a = 0; a < around; ++a) {
      const uint32_t p = ring + a, q = ring + (a + 1) % around;
      if (end) mesh.indices.insert(mesh.indices.end(), {centre, p, q});
      else mesh.indices.insert(mesh.indices.end(), {centre, q, p});
    }
  }
  // Bone b spans [b, b+1] * kLength / kBones; weights blend linearly between bone centres.
  const float boneLength = kLength / kBones;
  for (const auto& p : mesh.positions) {
    const float u = std::clamp(p.x / boneLength - 0.5f, 0.0f, kBones - 1.0f);
    const uint32_t b = std::min(static_cast<uint32_t>(u), static_cast<uint32_t>(kBones - 2));
    const float f = u - b;
    if (f <= 0.0f) { mesh.joints0.push_back({b, 0, 0, 0}); mesh.weights0.push_back({1, 0, 0, 0}); }
    else if (f >= 1.0f) { mesh.joints0.push_back({b + 1, 0, 0, 0}); mesh.weights0.push_back({1, 0, 0, 0}); }
    else { mesh.joints0.push_back({b, b + 1, 0, 0}); mesh.weights0.push_back({1 - f, f, 0, 0}); }
  }
  Character c;
  c.sourcePath = "procedural:dense";
  c.meshes.push_back(std::move(mesh));
  std::vector<BoneSpec> bones;
  for (int b = 0; b < kBones; ++b)
    bones.push_back({"bone" + std::to_string(b), b - 1, {b * boneLength, 0, 0}, {(b + 1) * boneLength, 0, 0}});
  const int first = addSkeleton(c, bones, 0, "dense_skin");
  AnimationClip wave;
  wave.name = "wave";
  wave.durationSec = 2.0f;
  for (int b = 1; b < kBones; ++b)
    wave.channels.push_back(sampledChannel(first + b, ChannelPath::Rotation, Interpolation::Linear, 2.0f, 16, [b](float t) {
      return quatValue(glm::angleAxis(0.25f * std::sin(glm::pi<float>() * t - 0.7f * b), glm::vec3(0, 0, 1)));
    }));
  c.clips.push_back(std::move(wave));
  return c;
}

}  // namespace animorph
