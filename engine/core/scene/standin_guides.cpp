#include "core/scene/standin_guides.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/scene/morph_runtime.h"
#include "core/rig/pose.h"
#include "core/scene/scene_frame.h"
#include "core/standin/standin.h"

namespace animorph {

namespace {

// Two unit vectors perpendicular to axis and to each other.
void perpendiculars(const glm::vec3& axis, glm::vec3& u, glm::vec3& v) {
  glm::vec3 n = glm::length(axis) > 1e-9f ? glm::normalize(axis) : glm::vec3(0.0f, 1.0f, 0.0f);
  u = std::abs(n.x) < 0.9f ? glm::normalize(glm::cross(n, glm::vec3(1, 0, 0)))
                           : glm::normalize(glm::cross(n, glm::vec3(0, 1, 0)));
  v = glm::cross(n, u);
}

}  // namespace

std::vector<glm::mat4> actorPoseGlobals(const Actor& actor, const Character& c, double timeSec) {
  const AnimationClip* clip = nullptr;
  float t = 0.0f;
  if (!c.clips.empty()) {
    clip = &c.clips[size_t(std::clamp(actor.clip, 0, int(c.clips.size()) - 1))];
    t = float(actorClipTimeSec(actor, *clip, timeSec));
  }
  return poseGlobals(c, clip, t);
}

StandinGuides standinGuides(const Actor& actor, const Character& c, const Standin& s, double timeSec) {
  StandinGuides g;
  g.actorId = actor.id;
  const auto globals = actorPoseGlobals(actor, c, timeSec);
  const glm::mat4 root = actor.transform.matrix();
  for (size_t i = 0; i < s.segments.size(); ++i) {
    const StandinSegment& seg = s.segments[i];
    StandinGuideSegment o;
    o.index = int(i);
    o.node = seg.node;
    o.nodeToWorld = seg.node >= 0 && seg.node < int(globals.size()) ? root * globals[size_t(seg.node)] : root;
    o.nodeScale = radiusScale(o.nodeToWorld);
    o.a = glm::vec3(o.nodeToWorld * glm::vec4(seg.a, 1.0f));
    o.b = glm::vec3(o.nodeToWorld * glm::vec4(seg.b, 1.0f));
    o.radius = seg.radius * o.nodeScale;
    g.segments.push_back(o);
  }
  return g;
}

std::vector<StandinGuides> projectStandinGuides(const Project& p, const std::string& baseDir, AssetCache& assets,
                                                double timeSec, const std::string& alsoActorId) {
  namespace fs = std::filesystem;
  std::vector<StandinGuides> out;
  if (!p.morph.enabled()) return out;
  double u = 0.0;
  const MorphStage stage = morphStageAt(p.morph, p.timeline, timeSec, u);
  const bool sourceShown = stage == MorphStage::Source || stage == MorphStage::Collapse || stage == MorphStage::Morph;
  const bool targetShown = stage == MorphStage::Target || stage == MorphStage::Expand || stage == MorphStage::Morph;
  for (const ActorMorph& am : p.morph.actors) {
    const Actor* actor = p.findActor(am.actorId);
    if (!actor || !actor->visible || actor->kind != ActorKind::Gltf || am.standin.segments.empty()) continue;
    const bool shown = (am.actorId == p.morph.sourceActorId && sourceShown) ||
                       (am.actorId == p.morph.targetActorId && targetShown) || am.actorId == alsoActorId;
    if (!shown) continue;
    fs::path path(actor->assetPath);
    const std::string abs = (path.is_absolute() ? path : fs::path(baseDir) / path).lexically_normal().string();
    const AssetCache::Entry& e = assets.get(abs);
    if (!e.character) continue;
    out.push_back(standinGuides(*actor, *e.character, am.standin, timeSec));
  }
  return out;
}

std::vector<StandinGuideLine> standinCapsuleLines(const StandinGuideSegment& s, int circleSteps) {
  std::vector<StandinGuideLine> out;
  const int n = std::max(4, circleSteps);
  const float r = s.radius;
  glm::vec3 axis = s.b - s.a;
  glm::vec3 dir = glm::length(axis) > 1e-9f ? glm::normalize(axis) : glm::vec3(0.0f, 1.0f, 0.0f);
  glm::vec3 u, v;
  perpendiculars(dir, u, v);
  auto add = [&](glm::vec3 p, glm::vec3 q) { out.push_back({p, q, s.index}); };
  add(s.a, s.b);  // the axis
  if (!(r > 0.0f)) return out;
  const float twoPi = 6.2831853f;
  for (const glm::vec3& c : {s.a, s.b})  // rings at the ends
    for (int i = 0; i < n; ++i) {
      float a0 = twoPi * float(i) / float(n), a1 = twoPi * float(i + 1) / float(n);
      add(c + r * (std::cos(a0) * u + std::sin(a0) * v), c + r * (std::cos(a1) * u + std::sin(a1) * v));
    }
  for (const glm::vec3& side : {u, v, -u, -v}) add(s.a + r * side, s.b + r * side);
  // Half circles over the caps, in the planes (u, dir) and (v, dir).
  for (int end = 0; end < 2; ++end) {
    const glm::vec3 c = end == 0 ? s.a : s.b;
    const glm::vec3 out_ = end == 0 ? -dir : dir;
    for (const glm::vec3& side : {u, v})
      for (int i = 0; i < n / 2; ++i) {
        float a0 = 3.14159265f * float(i) / float(n / 2), a1 = 3.14159265f * float(i + 1) / float(n / 2);
        add(c + r * (std::cos(a0) * side + std::sin(a0) * out_), c + r * (std::cos(a1) * side + std::sin(a1) * out_));
      }
  }
  return out;
}

glm::vec3 standinWorldToNode(const StandinGuideSegment& s, const glm::vec3& world) {
  return glm::vec3(glm::inverse(s.nodeToWorld) * glm::vec4(world, 1.0f));
}

}  // namespace animorph
