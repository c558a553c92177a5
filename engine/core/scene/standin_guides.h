#pragma once
// Where a morph actor's stand-in is at a time, for the viewport's "Stand-ins"
// overlay, picking and editing: each segment's posed ends and radius in world
// space, the matrix from its node's space to the world, and a wire capsule
// drawing (rings at the ends, four side lines, half circles over the caps).
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/project/asset_cache.h"
#include "core/project/project.h"
#include "core/rig/character.h"

namespace animorph {

struct StandinGuideSegment {
  int index = -1;              // into the actor's stand-in segments
  int node = -1;               // the segment's rig node
  glm::vec3 a{0.0f}, b{0.0f};  // posed ends, world space
  float radius = 0.0f;         // posed radius (m, world)
  glm::mat4 nodeToWorld{1.0f}; // actor transform * global(node): stored ends -> world
  float nodeScale = 1.0f;      // world radius / stored radius (mean axis scale of nodeToWorld)
};

struct StandinGuideLine {
  glm::vec3 a{0.0f}, b{0.0f};
  int segment = -1;
};

struct StandinGuides {
  std::string actorId;
  std::vector<StandinGuideSegment> segments;
};

// Node world matrices (without the actor transform) of actor's character c at
// scene time timeSec: its clip at (t - offset) * speed, looped or clamped.
std::vector<glm::mat4> actorPoseGlobals(const Actor& actor, const Character& c, double timeSec);

// The stand-in s of actor (character c) posed at scene time timeSec, the same
// pose the scene and the morph use (the actor's clip, offset, speed, loop).
StandinGuides standinGuides(const Actor& actor, const Character& c, const Standin& s, double timeSec);

// Guides of the visible morph actors whose asset loads (actors that fail are
// skipped: the scene reports them) and whose shape is on screen at timeSec:
// the source up to B, the target from C, both in between. alsoActorId (the
// selected actor) is shown at any time, so a stand-in can be edited while its
// actor is not drawn.
std::vector<StandinGuides> projectStandinGuides(const Project& p, const std::string& baseDir, AssetCache& assets,
                                                double timeSec, const std::string& alsoActorId = {});

// The wire capsule of one posed segment: `circleSteps` lines per ring.
std::vector<StandinGuideLine> standinCapsuleLines(const StandinGuideSegment& s, int circleSteps = 24);

// Stored (node-space) point of a world position for segment s.
glm::vec3 standinWorldToNode(const StandinGuideSegment& s, const glm::vec3& world);

}  // namespace animorph
