#include "demo/creature.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "demo/marching_tetrahedra.h"
#include "demo/rig_builder.h"

namespace animorph {
namespace {

struct Capsule {
  glm::vec3 a, b;
  float ra, rb;  // radius at a and at b
};

// Signed distance (negative inside) to a capsule whose radius varies linearly.
float capsuleDistance(const Capsule& c, const glm::vec3& p, float* along = nullptr) {
  const glm::vec3 ab = c.b - c.a;
  const float t = std::clamp(glm::dot(p - c.a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  if (along) *along = t;
  return glm::length(p - (c.a + t * ab)) - (c.ra + t * (c.rb - c.ra));
}

// Polynomial smooth minimum (blend width k).
float smoothMin(float a, float b, float k) {
  const float h = std::clamp(0.5f + 0.5f * (b - a) / k, 0.0f, 1.0f);
  return glm::mix(b, a, h) - k * h * (1.0f - h);
}

std::vector<BoneSpec> creatureBones() {
  std::vector<BoneSpec> b = {
      {"hips", -1, {0, 0.32f, 0}, {0, 0.33f, 0.28f}},
      {"chest", 0, {0, 0.33f, 0.28f}, {0, 0.34f, 0.52f}},
      {"neck", 1, {0, 0.34f, 0.52f}, {0, 0.40f, 0.68f}},
      {"head", 2, {0, 0.40f, 0.68f}, {0, 0.37f, 0.92f}},
      {"tail1", 0, {0, 0.32f, 0}, {0, 0.30f, -0.28f}},
      {"tail2", 4, {0, 0.30f, -0.28f}, {0, 0.27f, -0.55f}},
      {"tail3", 5, {0, 0.27f, -0.55f}, {0, 0.24f, -0.82f}},
  };
  // Legs sprawl sideways, then down to the ground: front from the chest, back from the hips.
  struct LegRoot { const char* name; int parent; float z; };
  const LegRoot roots[] = {{"front", 1, 0.46f}, {"back", 0, 0.06f}};
  for (const auto& r : roots)
    for (int side : {1, -1}) {
      const std::string s = side > 0 ? "_L" : "_R";
      const int upper = static_cast<int>(b.size());
      b.push_back({std::string(r.name) + "_upper" + s, r.parent, {0.09f * side, 0.30f, r.z}, {0.27f * side, 0.25f, r.z + 0.02f}});
      b.push_back({std::string(r.name) + "_lower" + s, upper, {0.27f * side, 0.25f, r.z + 0.02f}, {0.30f * side, 0.035f, r.z + 0.04f}});
    }
  return b;
}

std::vector<Capsule> creatureCapsules(const std::vector<BoneSpec>& bones) {
  // Radii at head and tail of each bone, in bone order.
  const float radii[][2] = {{0.125f, 0.13f}, {0.13f, 0.11f}, {0.075f, 0.07f}, {0.085f, 0.045f}, {0.11f, 0.08f},
                            {0.08f, 0.06f},  {0.06f, 0.04f}, {0.055f, 0.045f}, {0.045f, 0.04f}, {0.055f, 0.045f},
                            {0.045f, 0.04f}, {0.06f, 0.05f}, {0.05f, 0.04f},  {0.06f, 0.05f},  {0.05f, 0.04f}};
  std::vector<Capsule> caps;
  for (size_t i = 0; i < bones.size(); ++i) caps.push_back({bones[i].head, bones[i].tail, radii[i][0], radii[i][1]});
  return caps;
}

// The creature's skin: 128 x 64 texels (sRGB), rows from the back (top) to the belly (bottom):
// dark green bands across the back, lighter flanks, a pale belly, all in small overlapping
// scales (cells of 8 texels, every other row shifted by half, darker towards their rims).
// Repeats along the body (u), clamped across it (v).
TextureImage scalesTexture() {
  constexpr int kW = 128, kH = 64, kCell = 8;
  auto px = std::make_shared<std::vector<uint8_t>>(size_t(kW) * kH * 4);
  const glm::vec3 back(40, 92, 32), flank(96, 165, 58), belly(218, 206, 142);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float t = float(y) / float(kH - 1);
      glm::vec3 c = t < 0.5f ? glm::mix(back, flank, t / 0.5f) : glm::mix(flank, belly, (t - 0.5f) / 0.5f);
      if (t < 0.35f && (x / 16) % 2 == 0) c *= 0.62f;  // bands across the back
      const int row = y / kCell;
      const float cx = float(x) + (row % 2 ? 0.5f * kCell : 0.0f);
      const glm::vec2 d(std::fmod(cx, float(kCell)) - 0.5f * kCell, float(y % kCell) - 0.5f * kCell);
      const float rim = glm::clamp((glm::length(d) / (0.5f * kCell) - 0.55f) / 0.45f, 0.0f, 1.0f);
      c *= 1.0f - 0.38f * rim * rim;
      uint8_t* p = px->data() + (size_t(y) * kW + x) * 4;
      for (int k = 0; k < 3; ++k) p[k] = uint8_t(glm::clamp(c[k], 0.0f, 255.0f));
      p[3] = 255;
    }
  TextureImage img;
  img.name = "scales (generated)";
  img.width = kW;
  img.height = kH;
  img.rgba = std::move(px);
  img.wrapS = TextureWrap::Repeat;
  img.wrapT = TextureWrap::ClampToEdge;
  return img;
}

// Side projection: v from the top of the body (0) to the feet (1), u along the body, one
// texture width per two body heights; the same scales on both flanks.
std::vector<glm::vec2> sideProjection(const std::vector<glm::vec3>& positions) {
  Bounds b;
  for (const auto& p : positions) b.add(p);
  const float height = std::max(b.max.y - b.min.y, 1e-6f);
  std::vector<glm::vec2> uv;
  uv.reserve(positions.size());
  for (const auto& p : positions) uv.push_back({0.5f * (p.z - b.min.z) / height, (b.max.y - p.y) / height});
  return uv;
}

}  // namespace

Character makeCreatureCharacter() {
  const auto bones = creatureBones();
  const auto caps = creatureCapsules(bones);
  auto field = [&](const glm::vec3& p) {
    float d = capsuleDistance(caps[0], p);
    for (size_t i = 1; i < caps.size(); ++i) d = smoothMin(d, capsuleDistance(caps[i], p), 0.045f);
    return -d;  // inside positive
  };
  Bounds box;
  for (const auto& c : caps) {
    box.add(glm::min(c.a, c.b) - glm::vec3(std::max(c.ra, c.rb) + 0.06f));
    box.add(glm::max(c.a, c.b) + glm::vec3(std::max(c.ra, c.rb) + 0.06f));
  }
  TriangleMesh surface = marchingTetrahedra(field, box, 0.042f);

  Character c;
  c.sourcePath = "procedural:creature";
  Mesh mesh;
  mesh.name = "creature";
  mesh.positions = std::move(surface.positions);
  mesh.indices = std::move(surface.indices);
  // Normals from the field gradient (outward = direction of decreasing f).
  const float h = 1e-3f;
  for (const auto& p : mesh.positions) {
    glm::vec3 g(field(p + glm::vec3(h, 0, 0)) - field(p - glm::vec3(h, 0, 0)),
                field(p + glm::vec3(0, h, 0)) - field(p - glm::vec3(0, h, 0)),
                field(p + glm::vec3(0, 0, h)) - field(p - glm::vec3(0, 0, h)));
    float len = glm::length(g);
    mesh.normals.push_back(len > 0.0f ? -g / len : glm::vec3(0, 1, 0));
  }
  // Weights fall off with the fourth power of the distance to each bone
  // segment relative to the nearest one: smooth across neighbouring bones.
  std::vector<float> w(bones.size());
  for (const auto& p : mesh.positions) {
    float nearest = 1e30f;
    for (size_t b = 0; b < caps.size(); ++b) {
      Capsule axis = caps[b];
      axis.ra = axis.rb = 0.0f;
      w[b] = std::max(capsuleDistance(axis, p), 1e-4f);
      nearest = std::min(nearest, w[b]);
    }
    for (auto& d : w) {
      const float r = nearest / d;
      d = r * r * r * r;
    }
    glm::uvec4 j;
    glm::vec4 wt;
    topFourInfluences(w, j, wt);
    mesh.joints0.push_back(j);
    mesh.weights0.push_back(wt);
  }
  mesh.texcoords0 = sideProjection(mesh.positions);
  c.textures.push_back(scalesTexture());
  Material skin;
  skin.name = "scales";
  skin.baseColorTexture = 0;
  c.materials.push_back(skin);
  mesh.material = 0;
  c.meshes.push_back(std::move(mesh));
  const int first = addSkeleton(c, bones, 0, "creature_skin");
  auto node = [&](const char* name) {
    for (size_t b = 0; b < bones.size(); ++b)
      if (bones[b].name == name) return first + static_cast<int>(b);
    return -1;
  };

  // Walk cycle: diagonal pairs (front-left with back-right) half a cycle apart.
  const float duration = 2.0f;
  const float omega = 2.0f * glm::pi<float>() / duration;
  const int keys = 16;
  AnimationClip walk;
  walk.name = "walk";
  walk.durationSec = duration;
  auto yaw = [](float rad) { return glm::angleAxis(rad, glm::vec3(0, 1, 0)); };
  const glm::vec3 hipsRest = bones[0].head;
  walk.channels.push_back(sampledChannel(node("hips"), ChannelPath::Translation, Interpolation::CubicSpline, duration,
                                         keys, [&](float t) {
                                           return glm::vec4(hipsRest + glm::vec3(0, 0.012f * std::sin(2 * omega * t), 0), 0);
                                         }));
  walk.channels.push_back(sampledChannel(node("hips"), ChannelPath::Rotation, Interpolation::CubicSpline, duration, keys,
                                         [&](float t) { return quatValue(yaw(0.14f * std::sin(omega * t))); }));
  walk.channels.push_back(sampledChannel(node("chest"), ChannelPath::Rotation, Interpolation::CubicSpline, duration, keys,
                                         [&](float t) { return quatValue(yaw(-0.24f * std::sin(omega * t))); }));
  walk.channels.push_back(sampledChannel(node("neck"), ChannelPath::Rotation, Interpolation::CubicSpline, duration, keys,
                                         [&](float t) { return quatValue(yaw(0.12f * std::sin(omega * t))); }));
  const char* tail[] = {"tail1", "tail2", "tail3"};
  for (int k = 0; k < 3; ++k)
    walk.channels.push_back(sampledChannel(node(tail[k]), ChannelPath::Rotation, Interpolation::CubicSpline, duration,
                                           keys, [&, k](float t) {
                                             return quatValue(yaw(-0.22f * std::sin(omega * t - 0.9f * (k + 1))));
                                           }));
  struct Leg { const char* upper; const char* lower; float side; float phase; };
  const Leg legs[] = {{"front_upper_L", "front_lower_L", 1, 0.0f},
                      {"back_upper_R", "back_lower_R", -1, 0.0f},
                      {"front_upper_R", "front_lower_R", -1, glm::pi<float>()},
                      {"back_upper_L", "back_lower_L", 1, glm::pi<float>()}};
  for (const Leg& leg : legs) {
    // Swing about Y (forward/back); lift about Z while swinging forward.
    auto upper = [=](float t) {
      const float ph = omega * t + leg.phase;
      const float swing = 0.45f * std::cos(ph) * leg.side;
      const float lift = 0.35f * std::max(0.0f, std::sin(ph)) * leg.side;
      return quatValue(glm::angleAxis(swing, glm::vec3(0, 1, 0)) * glm::angleAxis(lift, glm::vec3(0, 0, 1)));
    };
    auto lower = [=](float t) {
      const float ph = omega * t + leg.phase;
      return quatValue(glm::angleAxis(-0.3f * std::max(0.0f, std::sin(ph)) * leg.side, glm::vec3(0, 0, 1)));
    };
    walk.channels.push_back(sampledChannel(node(leg.upper), ChannelPath::Rotation, Interpolation::Linear, duration, keys, upper));
    walk.channels.push_back(sampledChannel(node(leg.lower), ChannelPath::Rotation, Interpolation::Linear, duration, keys, lower));
  }
  c.clips.push_back(std::move(walk));
  return c;
}

}  // namespace animorph
