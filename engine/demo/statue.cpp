#include "demo/statue.h"

#include <cmath>

#include "core/blobtree/compile.h"
#include "core/project/animorphosis_project.h"
#include "core/doc/blobtree_commands.h"

namespace animorph {

namespace {

// A skeletal primitive whose surface, alone, lies `thickness` from its skeleton
// (intensity 2, stiffness 3: the surface is at 0.454 R).
BlobNode part(NodeType type, int id, const char* name, float thickness) {
  BlobNode n = makeBlobNode(type, id, name);
  n.floatParam("radius") = FloatTrack(thickness / 0.4540f);
  n.floatParam("intensity") = FloatTrack(2.0f);
  return n;
}

// The statue's materials (sRGB): its particles keep them as they fly (convertToParticles colours
// each particle by the surface point it came from), so the explosion shows where each piece was.
constexpr glm::vec3 kGranite{0.46f, 0.24f, 0.2f}, kBronze{0.74f, 0.48f, 0.22f}, kMarble{0.9f, 0.88f, 0.82f},
    kGold{0.96f, 0.76f, 0.26f};

BlobNode segment(int id, const char* name, glm::vec3 a, glm::vec3 b, float thickness, glm::vec3 color) {
  BlobNode n = part(NodeType::Segment, id, name, thickness);
  n.vec3Param("color") = Vec3Track(color);
  n.vec3Param("a") = Vec3Track(a);
  n.vec3Param("b") = Vec3Track(b);
  return n;
}

}  // namespace

BlobTree makeStatue() {
  BlobTree t;
  t.root = makeBlobNode(NodeType::Blend, 1, "statue");
  BlobNode pedestal = part(NodeType::Cylinder, 2, "pedestal", 0.07f);
  pedestal.vec3Param("a") = Vec3Track(glm::vec3(0.0f, 0.1f, 0.0f));
  pedestal.vec3Param("b") = Vec3Track(glm::vec3(0.0f, 0.3f, 0.0f));
  pedestal.floatParam("skeletonRadius") = FloatTrack(0.22f);
  pedestal.vec3Param("color") = Vec3Track(kGranite);
  auto& c = t.root.children;
  c.push_back(pedestal);
  c.push_back(segment(3, "left leg", {-0.12f, 0.45f, 0.0f}, {-0.09f, 0.95f, 0.0f}, 0.09f, kBronze));
  c.push_back(segment(4, "right leg", {0.12f, 0.45f, 0.0f}, {0.09f, 0.95f, 0.0f}, 0.09f, kBronze));
  c.push_back(segment(5, "torso", {0.0f, 0.98f, 0.0f}, {0.0f, 1.38f, 0.0f}, 0.16f, kMarble));
  c.push_back(segment(6, "shoulders", {-0.2f, 1.42f, 0.0f}, {0.2f, 1.42f, 0.0f}, 0.085f, kMarble));
  c.push_back(segment(7, "left arm", {-0.22f, 1.42f, 0.0f}, {-0.42f, 1.8f, 0.05f}, 0.07f, kBronze));
  c.push_back(segment(8, "right arm", {0.22f, 1.42f, 0.0f}, {0.42f, 1.8f, 0.05f}, 0.07f, kBronze));
  BlobNode head = part(NodeType::Point, 9, "head", 0.12f);
  head.vec3Param("center") = Vec3Track(glm::vec3(0.0f, 1.66f, 0.0f));
  head.vec3Param("color") = Vec3Track(kGold);
  c.push_back(head);
  return t;
}

ParticleAnimorphosisSettings statueDemoSettings(const StatueDemoOptions& o) {
  ParticleAnimorphosisSettings s;
  s.startSec = o.holdSec;
  s.tolerance = o.tolerance;
  s.quantum = o.quantum;
  s.explosion.rateHz = o.rateHz;
  ParticleForces& e = s.explosion.forces;
  s.explosion.durationSec = o.durationSec;
  s.explosion.seed = 1;
  e.explosion.centre = glm::vec3(0.0f, 1.1f, 0.06f);
  e.explosion.energy = 12.0f;
  e.explosion.falloff = 0.6f;
  e.drag = 0.3f;
  e.restitution = 0.25f;
  e.friction = 0.3f;
  ParticleForces& v = s.vortex.forces;
  s.vortex.seed = 2;
  v.explosion.enabled = false;
  v.gravity = glm::vec3(0.0f);
  v.drag = 0.0f;
  v.vortex.enabled = true;
  v.vortex.centre = glm::vec3(0.0f);
  v.vortex.axis = glm::vec3(0.0f, 1.0f, 0.0f);
  v.vortex.swirl = 3.0f;
  v.vortex.radius = 0.6f;
  v.vortex.inward = -0.5f;  // forward it throws outward; played backwards it pulls inward
  v.vortex.lift = 0.5f;
  v.vortex.coupling = 1.5f;
  return s;
}

Result<StatueDemo> makeStatueDemo(const StatueDemoOptions& o) {
  StatueDemo d;
  BlobTree statue = makeStatue();
  ConvertToParticlesSettings cs;
  cs.count = o.particles;
  auto conv = convertToParticles(compileFieldProgram(statue, 0.0), cs);
  if (!conv) return Error{"statue demo: " + conv.error()};
  d.conversion = conv->report;
  auto anim = makeParticleAnimorphosis(conv->tree, statueDemoSettings(o));
  if (!anim) return Error{"statue demo: " + anim.error()};
  d.animorphosis = std::move(*anim);
  Project& p = d.project;
  p.name = "Statue: explosion and vortex";
  p.timeline.fps = 24.0;
  p.timeline.frameStart = 0;
  p.timeline.frameEnd = int(std::lround(p.timeline.secToFrame(d.animorphosis.endSec + o.holdSec)));
  p.view.showSkeleton = false;
  Actor a = makeBlobTreeActor(p, "Exploding");
  a.blobTree = d.animorphosis.exploding;
  a.loop = false;
  p.actors.push_back(a);
  Actor b = makeBlobTreeActor(p, "Gathering");
  b.blobTree = d.animorphosis.gathering;
  b.loop = false;
  p.actors.push_back(b);
  p.animorphosis.sourceActorId = a.id;
  p.animorphosis.targetActorId = b.id;
  p.animorphosis.startSec = d.animorphosis.startSec;
  p.animorphosis.endSec = d.animorphosis.endSec;
  p.animorphosis.globalS = defaultSCurve();
  p.animorphosis.graph = d.animorphosis.graph;
  if (auto s = checkAnimorphosis(p); !s) return Error{"statue demo: " + s.error()};
  return d;
}

}  // namespace animorph
