#include "demo/blob_creature.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace animorph {

namespace {

struct Builder {
  int nextId = 1;

  BlobNode node(NodeType t, const std::string& name) { return makeBlobNode(t, nextId++, name); }

  BlobNode segment(const std::string& name, glm::vec3 a, glm::vec3 b, float radius) {
    BlobNode s = node(NodeType::ConvSegment, name);
    s.vec3Param("a") = Vec3Track(a);
    s.vec3Param("b") = Vec3Track(b);
    s.floatParam("radius") = FloatTrack(radius);
    s.floatParam("sharpness") = FloatTrack(14.0f);
    return s;
  }

  BlobNode frame(const std::string& name, glm::vec3 translation) {
    BlobNode f = node(NodeType::Frame, name);
    f.vec3Param("translation") = Vec3Track(translation);
    return f;
  }
};

// A rotation about `axis` swinging between -amp and +amp over the loop, starting at phase.
QuatTrack swing(glm::vec3 axis, float amp, float phase) {
  QuatTrack q;
  q.clearKeys();
  for (int k = 0; k <= 8; ++k) {
    double t = kBlobCreatureLoopSec * k / 8.0;
    float a = amp * std::sin(float(2.0 * M_PI * t / kBlobCreatureLoopSec) + phase);
    q.setKey(t, glm::angleAxis(a, glm::normalize(axis)));
  }
  return q;
}

}  // namespace

BlobTree makeBlobCreature() {
  Builder b;
  BlobTree tree;
  tree.threshold = FloatTrack(1.0f);
  tree.root = b.node(NodeType::Blend, "creature");

  BlobNode body = b.frame("body", {0, 0.55f, 0});
  Vec3Track bob;
  bob.clearKeys();
  for (int k = 0; k <= 4; ++k) {
    double t = kBlobCreatureLoopSec * k / 4.0;
    bob.setKey(t, glm::vec3(0, 0.55f + 0.02f * std::sin(float(4.0 * M_PI * t / kBlobCreatureLoopSec)), 0));
  }
  body.vec3Param("translation") = bob;

  BlobNode torso = b.segment("torso", {-0.28f, 0, 0}, {0.28f, 0.03f, 0}, 0.15f);
  FloatTrack breath;
  breath.clearKeys();
  breath.setKey(0.0, 0.15f);
  breath.setKey(kBlobCreatureLoopSec / 2, 0.17f);
  breath.setKey(kBlobCreatureLoopSec, 0.15f);
  torso.floatParam("radius") = breath;
  body.children.push_back(torso);

  BlobNode head = b.frame("head", {0.4f, 0.14f, 0});
  head.quatParam("rotation") = swing({0, 0, 1}, 0.15f, 0.0f);
  head.children.push_back(b.segment("skull", {-0.04f, 0, 0}, {0.06f, 0.02f, 0}, 0.1f));
  head.children.push_back(b.segment("snout", {0.06f, 0.0f, 0}, {0.16f, -0.04f, 0}, 0.055f));
  head.children.push_back(b.segment("ear_l", {0.0f, 0.08f, 0.05f}, {-0.04f, 0.18f, 0.08f}, 0.03f));
  head.children.push_back(b.segment("ear_r", {0.0f, 0.08f, -0.05f}, {-0.04f, 0.18f, -0.08f}, 0.03f));
  body.children.push_back(head);

  const struct {
    const char* name;
    glm::vec3 hip;
    float phase;
  } legs[] = {{"leg_front_left", {0.2f, -0.06f, 0.11f}, 0.0f},
              {"leg_front_right", {0.2f, -0.06f, -0.11f}, float(M_PI)},
              {"leg_back_left", {-0.2f, -0.06f, 0.11f}, float(M_PI)},
              {"leg_back_right", {-0.2f, -0.06f, -0.11f}, 0.0f}};
  for (const auto& l : legs) {
    BlobNode hip = b.frame(l.name, l.hip);
    hip.quatParam("rotation") = swing({0, 0, 1}, 0.45f, l.phase);
    hip.children.push_back(b.segment(std::string(l.name) + "_thigh", {0, 0, 0}, {0.02f, -0.2f, 0}, 0.055f));
    BlobNode knee = b.frame(std::string(l.name) + "_knee", {0.02f, -0.2f, 0});
    knee.quatParam("rotation") = swing({0, 0, 1}, 0.3f, l.phase - 1.2f);
    knee.children.push_back(b.segment(std::string(l.name) + "_shin", {0, 0, 0}, {-0.02f, -0.19f, 0}, 0.042f));
    knee.children.push_back(b.segment(std::string(l.name) + "_paw", {-0.02f, -0.19f, 0}, {0.05f, -0.2f, 0}, 0.04f));
    hip.children.push_back(knee);
    body.children.push_back(hip);
  }

  BlobNode tail = b.node(NodeType::SplineOfNodes, "tail");
  ControlPoints pts;
  pts.push_back(Vec3Track(glm::vec3(-0.3f, 0.02f, 0)));
  pts.push_back(Vec3Track(glm::vec3(-0.45f, 0.08f, 0)));
  for (int p = 0; p < 2; ++p) {
    Vec3Track sway;
    sway.clearKeys();
    glm::vec3 base = p == 0 ? glm::vec3(-0.6f, 0.16f, 0) : glm::vec3(-0.72f, 0.28f, 0);
    float amp = p == 0 ? 0.08f : 0.16f;
    for (int k = 0; k <= 4; ++k) {
      double t = kBlobCreatureLoopSec * k / 4.0;
      float s = std::sin(float(2.0 * M_PI * t / kBlobCreatureLoopSec) - 0.6f * float(p));
      sway.setKey(t, base + glm::vec3(0, 0, amp * s));
    }
    pts.push_back(sway);
  }
  tail.pointsParam("points") = pts;
  tail.floatParam("count") = FloatTrack(10.0f);
  tail.floatParam("scaleStart") = FloatTrack(1.0f);
  tail.floatParam("scaleEnd") = FloatTrack(0.6f);
  BlobNode bead = b.node(NodeType::Point, "tail_bead");
  bead.vec3Param("center") = Vec3Track(glm::vec3(0));
  bead.floatParam("radius") = FloatTrack(0.14f);
  bead.floatParam("intensity") = FloatTrack(2.0f);
  tail.children.push_back(bead);
  body.children.push_back(tail);

  tree.root.children.push_back(body);
  return tree;
}

}  // namespace animorph
