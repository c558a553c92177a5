#include "demo/dino_dragon.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>

#include <glm/gtc/quaternion.hpp>

namespace animorph {

namespace {

constexpr float kThreshold = 0.5f;
constexpr float kTwoPi = 6.2831853f;

// Fibre layers of a body part: the fraction of the local radius at which a
// ring of fibres runs, and how many fibres the ring holds.
struct Layer {
  float rho;
  int count;
};
const std::vector<Layer> kBodyLayers = {{0.0f, 1}, {0.25f, 6}, {0.45f, 11}, {0.62f, 15}, {0.78f, 19}};
const std::vector<Layer> kBoneLayers = {{0.0f, 1}, {0.5f, 6}};

// Offset of an axis point at a clip time (the tail's sway); empty: static.
using Sway = std::function<glm::vec3(int axisPoint, double timeSec)>;

struct PartSpec {
  std::string name;
  std::vector<glm::vec3> axis;  // in the joint's frame, >= 2 points
  std::vector<float> radii;     // surface radius at each axis point
  const std::vector<Layer>* layers = &kBodyLayers;
  Sway sway;                    // animates every fibre's control points
  double loopSec = 1.0;         // period of the sway / breath keys
  float breath = 0.0f;          // > 0: the fibres' points swell by this fraction at mid-loop
};

float potential(float d, float radius) {
  float x = d / radius;
  if (x >= 1.0f) return 0.0f;
  float w = 1.0f - x * x;
  return w * w * w;
}

// Intensity that puts the surface of a straight bundle of fibres at its
// radius r: the bundle's field at distance r from the axis (averaged over
// angles, away from the ends), with points of radius r every `spacing` along
// each fibre, set to the threshold.
float bundleIntensity(const std::vector<Layer>& layers, float spacing) {
  const float r = 1.0f, radius = 1.0f;
  int reach = int(std::ceil(radius / spacing)) + 1;
  double sum = 0.0;
  const int angles = 16;
  for (int a = 0; a < angles; ++a) {
    float phi = kTwoPi * float(a) / angles;
    glm::vec2 probe = r * glm::vec2(std::cos(phi), std::sin(phi));
    for (size_t l = 0; l < layers.size(); ++l)
      for (int i = 0; i < layers[l].count; ++i) {
        float theta = kTwoPi * (float(i) + 0.5f * float(l)) / float(layers[l].count);
        glm::vec2 p = layers[l].rho * r * glm::vec2(std::cos(theta), std::sin(theta));
        float dxy = glm::length(probe - p);
        for (int k = -reach; k <= reach; ++k) sum += potential(std::hypot(dxy, float(k) * spacing), radius);
      }
  }
  return float(kThreshold / (sum / angles));
}

// Two unit vectors perpendicular to the tangent of the polyline at point j.
void crossSection(const std::vector<glm::vec3>& axis, size_t j, glm::vec3& u, glm::vec3& v) {
  glm::vec3 t = axis[std::min(j + 1, axis.size() - 1)] - axis[j == 0 ? 0 : j - 1];
  t = glm::normalize(t);
  glm::vec3 ref = std::abs(t.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  u = glm::normalize(glm::cross(t, ref));
  v = glm::cross(u, t);
}

float polylineLength(const std::vector<glm::vec3>& pts) {
  float len = 0.0f;
  for (size_t i = 1; i < pts.size(); ++i) len += glm::length(pts[i] - pts[i - 1]);
  return len;
}

// A track sampled from f at `samples` + 1 evenly spaced times over one loop
// (the last key equals the first, so the clip loops smoothly).
template <class T>
Track<T> loopTrack(double loopSec, int samples, const std::function<T(double)>& f) {
  Track<T> track;
  track.clearKeys();
  for (int k = 0; k <= samples; ++k) {
    double t = loopSec * k / samples;
    track.setKey(t, f(k == samples ? 0.0 : t));
  }
  return track;
}

QuatTrack rotationLoop(double loopSec, glm::vec3 axis, const std::function<float(double)>& angle) {
  axis = glm::normalize(axis);
  return loopTrack<glm::quat>(loopSec, 8, [&](double t) { return glm::angleAxis(angle(t), axis); });
}

struct Builder {
  int nextId = 1;

  BlobNode node(NodeType t, const std::string& name) { return makeBlobNode(t, nextId++, name); }

  BlobNode frame(const std::string& name, glm::vec3 translation) {
    BlobNode f = node(NodeType::Frame, name);
    f.vec3Param("translation") = Vec3Track(translation);
    return f;
  }

  // A spline-of-nodes of `count` copies of a point primitive of radius 1
  // (scaled from scaleStart to scaleEnd along the spline) through `points`.
  BlobNode pointSpline(const std::string& name, ControlPoints points, float count, float scaleStart, float scaleEnd,
                       float intensity, const std::string& pointName) {
    BlobNode spline = node(NodeType::SplineOfNodes, name);
    spline.pointsParam("points") = std::move(points);
    spline.floatParam("count") = FloatTrack(count);
    spline.floatParam("scaleStart") = FloatTrack(scaleStart);
    spline.floatParam("scaleEnd") = FloatTrack(scaleEnd);
    BlobNode point = node(NodeType::Point, pointName);
    point.vec3Param("center") = Vec3Track(glm::vec3(0.0f));
    point.floatParam("radius") = FloatTrack(1.0f);
    point.floatParam("intensity") = FloatTrack(intensity);
    spline.children.push_back(std::move(point));
    return spline;
  }

  // A blend of spline-of-nodes fibres running along the part's axis, ring
  // after ring; each fibre copies a point primitive whose radius follows the
  // part's radius from the first axis point to the last.
  BlobNode part(std::string name, std::vector<glm::vec3> axis, std::vector<float> radii,
                const std::vector<Layer>* layers = &kBodyLayers) {
    PartSpec spec;
    spec.name = std::move(name);
    spec.axis = std::move(axis);
    spec.radii = std::move(radii);
    spec.layers = layers;
    return part(spec);
  }

  BlobNode part(const PartSpec& spec) {
    BlobNode bundle = node(NodeType::Blend, spec.name);
    float length = polylineLength(spec.axis);
    float meanRadius = 0.0f;
    for (float r : spec.radii) meanRadius += r / float(spec.radii.size());
    float minRadius = *std::min_element(spec.radii.begin(), spec.radii.end());
    // Copies close enough for the thinnest end to stay one smooth tube.
    int copies = std::clamp(int(std::lround(length / (0.8f * minRadius))) + 1, 3, 48);
    float spacing = length / float(copies - 1) / meanRadius;  // in units of the radius
    float intensity = bundleIntensity(*spec.layers, spacing);
    int fibre = 0;
    for (size_t l = 0; l < spec.layers->size(); ++l) {
      const Layer& layer = (*spec.layers)[l];
      for (int i = 0; i < layer.count; ++i, ++fibre) {
        float theta = kTwoPi * (float(i) + 0.5f * float(l)) / float(layer.count);
        std::string name = spec.name + "_f" + std::to_string(fibre);
        ControlPoints pts;
        for (size_t j = 0; j < spec.axis.size(); ++j) {
          glm::vec3 u, v;
          crossSection(spec.axis, j, u, v);
          glm::vec3 p = spec.axis[j] + layer.rho * spec.radii[j] * (std::cos(theta) * u + std::sin(theta) * v);
          if (!spec.sway) {
            pts.push_back(Vec3Track(p));
          } else {
            int jj = int(j);
            pts.push_back(loopTrack<glm::vec3>(spec.loopSec, 8, [&](double t) { return p + spec.sway(jj, t); }));
          }
        }
        BlobNode spline = pointSpline(name, std::move(pts), float(copies), spec.radii.front(), spec.radii.back(),
                                      intensity, name + "_pt");
        if (spec.breath > 0.0f) {
          float swell = spec.breath;
          spline.children[0].floatParam("radius") = loopTrack<float>(spec.loopSec, 4, [&](double t) {
            return 1.0f + swell * 0.5f * (1.0f - std::cos(kTwoPi * float(t / spec.loopSec)));
          });
        }
        bundle.children.push_back(std::move(spline));
      }
    }
    return bundle;
  }

  // A small cone (tooth, claw, horn tip) from a to b.
  BlobNode cone(const std::string& name, glm::vec3 a, glm::vec3 b, float ra, float rb, float radius) {
    BlobNode c = node(NodeType::Cone, name);
    c.vec3Param("a") = Vec3Track(a);
    c.vec3Param("b") = Vec3Track(b);
    c.floatParam("radiusA") = FloatTrack(ra);
    c.floatParam("radiusB") = FloatTrack(rb);
    c.floatParam("radius") = FloatTrack(radius);
    return c;
  }
};

// Proportions and motion of one member of the family.
struct BodyStyle {
  bool dragon = false;
  double loopSec = kDinosaurLoopSec;
  float neckLength = 0.32f;
  float tailLength = 1.9f;
  float girth = 1.0f;  // torso radius scale
};

// Angle of a leg joint over the clip: the dinosaur walks (phase: 0 left, pi
// right), the dragon holds its legs tucked and lets them dangle a little.
struct LegMotion {
  std::function<float(double)> hip, knee, ankle, toe;
};

LegMotion legMotion(const BodyStyle& s, float phase) {
  double w = kTwoPi / s.loopSec;
  if (!s.dragon) {
    return {[=](double t) { return 0.42f * float(std::sin(w * t + phase)); },
            [=](double t) { return -0.15f - 0.4f * float(std::max(0.0, std::sin(w * t + phase + 1.2))); },
            [=](double t) { return 0.25f * float(std::max(0.0, std::sin(w * t + phase + 1.2))) -
                                   0.2f * float(std::sin(w * t + phase)); },
            [=](double t) { return 0.3f * float(std::max(0.0, -std::sin(w * t + phase - 0.6))); }};
  }
  return {[=](double t) { return -1.25f + 0.06f * float(std::sin(w * t + phase)); },
          [=](double t) { return 0.35f + 0.08f * float(std::sin(w * t + phase - 0.8)); },
          [=](double) { return 0.2f; }, [=](double) { return 0.4f; }};
}

BlobNode buildLeg(Builder& b, const BodyStyle& s, const std::string& side, float z, float phase) {
  LegMotion m = legMotion(s, phase);
  const glm::vec3 pitch(0, 0, 1);
  BlobNode hip = b.frame("hip_" + side, {0.02f, -0.12f, z});
  hip.quatParam("rotation") = rotationLoop(s.loopSec, pitch, m.hip);
  hip.children.push_back(b.part("thigh_" + side, {{0, 0.05f, 0}, {0.08f, -0.3f, 0}, {0.1f, -0.58f, 0}}, {0.2f, 0.16f, 0.11f}));
  BlobNode knee = b.frame("knee_" + side, {0.1f, -0.58f, 0});
  knee.quatParam("rotation") = rotationLoop(s.loopSec, pitch, m.knee);
  knee.children.push_back(b.part("shin_" + side, {{0, 0, 0}, {-0.06f, -0.25f, 0}, {-0.1f, -0.48f, 0}}, {0.1f, 0.08f, 0.065f}));
  BlobNode ankle = b.frame("ankle_" + side, {-0.1f, -0.48f, 0});
  ankle.quatParam("rotation") = rotationLoop(s.loopSec, pitch, m.ankle);
  ankle.children.push_back(b.part("foot_" + side, {{0, 0, 0}, {0.02f, -0.14f, 0}, {0.04f, -0.26f, 0}}, {0.065f, 0.06f, 0.055f}));
  BlobNode toe = b.frame("toe_" + side, {0.04f, -0.26f, 0});
  toe.quatParam("rotation") = rotationLoop(s.loopSec, pitch, m.toe);
  toe.children.push_back(b.part("toes_" + side, {{-0.04f, 0, 0}, {0.1f, -0.02f, 0}, {0.24f, -0.03f, 0}}, {0.06f, 0.05f, 0.035f}));
  if (!s.dragon)
    for (int c = 0; c < 3; ++c) {
      float dz = 0.05f * float(c - 1);
      toe.children.push_back(b.cone("claw_" + side + std::to_string(c), {0.22f, -0.03f, dz}, {0.33f, -0.07f, 1.4f * dz},
                                    0.025f, 0.004f, 0.05f));
    }
  ankle.children.push_back(std::move(toe));
  knee.children.push_back(std::move(ankle));
  hip.children.push_back(std::move(knee));
  return hip;
}

BlobNode buildArm(Builder& b, const BodyStyle& s, const std::string& side, float z, float phase) {
  double w = kTwoPi / s.loopSec;
  float swing = s.dragon ? 0.05f : 0.15f;
  BlobNode arm = b.frame("arm_" + side, {0.42f, -0.12f, z});
  arm.quatParam("rotation") =
      rotationLoop(s.loopSec, {0, 0, 1}, [=](double t) { return 0.3f + swing * float(std::sin(w * t + phase)); });
  arm.children.push_back(b.part("upperarm_" + side, {{0, 0, 0}, {0.04f, -0.12f, 0}, {0.06f, -0.22f, 0}}, {0.065f, 0.055f, 0.045f}));
  BlobNode elbow = b.frame("elbow_" + side, {0.06f, -0.22f, 0});
  elbow.quatParam("rotation") =
      rotationLoop(s.loopSec, {0, 0, 1}, [=](double t) { return 1.1f + swing * float(std::sin(w * t + phase - 0.5)); });
  elbow.children.push_back(b.part("forearm_" + side, {{0, 0, 0}, {0.0f, -0.1f, 0}, {0.0f, -0.2f, 0}}, {0.045f, 0.04f, 0.035f}));
  if (!s.dragon)
    for (int c = 0; c < 2; ++c) {
      float dz = 0.03f * (c == 0 ? -1.0f : 1.0f);
      elbow.children.push_back(b.cone("handclaw_" + side + std::to_string(c), {0.0f, -0.19f, dz}, {0.05f, -0.27f, dz},
                                      0.018f, 0.003f, 0.035f));
    }
  arm.children.push_back(std::move(elbow));
  return arm;
}

// A wing's membrane: a union of Coons patches tiling the bilinear surface of
// the four corners (front root, front tip, back root, back tip), billowing
// downwards by `sag` in its middle.
BlobNode membrane(Builder& b, const std::string& name, glm::vec3 frontRoot, glm::vec3 frontTip, glm::vec3 backRoot,
                  glm::vec3 backTip, float sag, int cells) {
  auto surface = [&](float u, float v) {  // u: root -> tip, v: front -> back
    glm::vec3 front = glm::mix(frontRoot, frontTip, u), back = glm::mix(backRoot, backTip, u);
    glm::vec3 p = glm::mix(front, back, v);
    p.y -= sag * std::sin(3.14159265f * u) * std::sin(3.14159265f * v);
    return p;
  };
  BlobNode u = b.node(NodeType::Union, name);
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      float u0 = float(i) / cells, u1 = float(i + 1) / cells, v0 = float(j) / cells, v1 = float(j + 1) / cells;
      BlobNode patch = b.node(NodeType::CoonsPatch, "");
      auto edge = [&](glm::vec3 p, glm::vec3 q) { return ControlPoints{Vec3Track(p), Vec3Track(q)}; };
      patch.pointsParam("bottom") = edge(surface(u0, v0), surface(u1, v0));
      patch.pointsParam("top") = edge(surface(u0, v1), surface(u1, v1));
      patch.pointsParam("left") = edge(surface(u0, v0), surface(u0, v1));
      patch.pointsParam("right") = edge(surface(u1, v0), surface(u1, v1));
      patch.floatParam("resolution") = FloatTrack(1.0f);
      patch.floatParam("radius") = FloatTrack(0.07f);
      patch.floatParam("intensity") = FloatTrack(1.0f);
      u.children.push_back(std::move(patch));
    }
  return u;
}

constexpr int kWingCells = 35;  // membrane patches per side of each of a wing's two panels

// A wing under the back frame: side "l" extends towards +Z, "r" towards -Z.
// The shoulder flaps about the body axis, the hand follows with a lag.
BlobNode buildWing(Builder& b, const BodyStyle& s, const std::string& side) {
  float m = side == "l" ? 1.0f : -1.0f;
  auto z = [&](glm::vec3 p) { return glm::vec3(p.x, p.y, m * p.z); };
  double w = kTwoPi / s.loopSec;
  BlobNode wing = b.frame("wing_" + side, z({-0.05f, 0.0f, 0.16f}));
  wing.quatParam("rotation") =
      rotationLoop(s.loopSec, {1, 0, 0}, [=](double t) { return -m * (0.15f + 0.7f * float(std::sin(w * t))); });
  glm::vec3 elbowAt = z({0.15f, 0.05f, 1.0f});
  wing.children.push_back(b.part("wingarm_" + side, {z({0.05f, 0, 0}), z({0.12f, 0.04f, 0.5f}), elbowAt},
                                  {0.08f, 0.06f, 0.05f}, &kBoneLayers));
  wing.children.push_back(membrane(b, "membrane_in_" + side, z({0.05f, 0, 0}), elbowAt, z({-0.6f, 0, 0}),
                                   z({-0.55f, 0, 0.95f}), 0.08f, kWingCells));
  BlobNode hand = b.frame("wing_hand_" + side, elbowAt);
  hand.quatParam("rotation") =
      rotationLoop(s.loopSec, {1, 0, 0}, [=](double t) { return -m * 0.35f * float(std::sin(w * t - 0.9)); });
  hand.children.push_back(b.part("wingfinger_" + side + "0", {{0, 0, 0}, z({0.1f, 0, 0.6f}), z({0.15f, -0.02f, 1.2f})},
                                  {0.05f, 0.04f, 0.03f}, &kBoneLayers));
  hand.children.push_back(b.part("wingfinger_" + side + "1", {{0, 0, 0}, z({-0.15f, -0.02f, 0.45f}), z({-0.14f, -0.04f, 0.88f})},
                                  {0.04f, 0.032f, 0.026f}, &kBoneLayers));
  hand.children.push_back(membrane(b, "membrane_out_" + side, {0, 0, 0}, z({0.15f, -0.02f, 1.2f}), z({-0.7f, -0.05f, -0.05f}),
                                   z({0.02f, -0.04f, 1.12f}), 0.06f, kWingCells));
  wing.children.push_back(std::move(hand));
  return wing;
}

// Four significant digits, so that the demo files stay small (a float written
// with its shortest decimal form) without changing the shapes.
float roundSignificant(float x) {
  if (x == 0.0f || !std::isfinite(x)) return x;
  double scale = std::pow(10.0, 3 - int(std::floor(std::log10(std::abs(double(x))))));
  return float(std::round(double(x) * scale) / scale);
}

void roundValues(BlobNode& n) {
  auto roundVec = [](Vec3Track& t) {
    for (auto& k : t.keys())
      for (int c = 0; c < 3; ++c) k.value[c] = roundSignificant(k.value[c]);
  };
  for (ParamValue& p : n.params) {
    if (auto* f = std::get_if<FloatTrack>(&p))
      for (auto& k : f->keys()) k.value = roundSignificant(k.value);
    else if (auto* v = std::get_if<Vec3Track>(&p))
      roundVec(*v);
    else if (auto* pts = std::get_if<ControlPoints>(&p))
      for (auto& t : *pts) roundVec(t);
  }
  for (BlobNode& c : n.children) roundValues(c);
}

// The creatures' colours (sRGB): the dinosaur olive green with darker stripes along its body (every
// other fibre), a cream belly, orange quills and ivory teeth and claws; the dragon crimson with
// darker stripes, a golden belly, orange wing membranes and ivory horns. `part` is the name of the
// nearest named ancestor (a fibre's point is "<part>_f<k>_pt"; quills and membrane patches are
// unnamed under their spline or union).
struct Palette {
  glm::vec3 skin, stripe, belly, spike, membrane;
};
const Palette kDinosaurColors{{0.42f, 0.58f, 0.25f}, {0.24f, 0.36f, 0.15f}, {0.86f, 0.80f, 0.56f},
                              {0.85f, 0.46f, 0.14f}, {0.85f, 0.46f, 0.14f}};
const Palette kDragonColors{{0.66f, 0.13f, 0.10f}, {0.40f, 0.06f, 0.08f}, {0.92f, 0.70f, 0.26f},
                            {0.95f, 0.93f, 0.84f}, {0.96f, 0.52f, 0.16f}};
const glm::vec3 kIvory{0.95f, 0.93f, 0.84f};

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

void paint(BlobNode& n, const Palette& c, const std::string& part) {
  const std::string& here = n.name.empty() ? part : n.name;
  if (paramIndex(n.type, "color") >= 0) {
    glm::vec3 color = c.skin;
    if (startsWith(here, "belly")) color = c.belly;
    else if (startsWith(here, "quill") || startsWith(here, "horn")) color = c.spike;
    else if (startsWith(here, "membrane")) color = c.membrane;
    else if (startsWith(here, "tooth") || startsWith(here, "lowtooth") || here.find("claw") != std::string::npos)
      color = kIvory;
    else if (size_t f = here.rfind("_f"); f != std::string::npos && f + 2 < here.size()) {
      const int fibre = std::atoi(here.c_str() + f + 2);
      if (fibre % 2 == 1) color = c.stripe;
    }
    n.vec3Param("color") = Vec3Track(color);
  }
  for (BlobNode& k : n.children) paint(k, c, here);
}

// The back between the shoulders: the dinosaur's quills, the dragon's wings.
BlobNode buildBack(Builder& b, const BodyStyle& s) {
  BlobNode back = b.frame("back", {0.2f, 0.26f * s.girth, 0});
  if (!s.dragon) {
    for (int row = 0; row < 5; ++row)
      for (int q = 0; q < 22; ++q) {
        float x = -0.7f + 0.05f * float(q), zq = 0.05f * float(row - 2);
        float h = 0.07f + 0.05f * std::sin(3.14159265f * float(q) / 21.0f);
        ControlPoints pts = {Vec3Track(glm::vec3(x, -0.02f - 0.02f * std::abs(float(row - 2)), zq)),
                             Vec3Track(glm::vec3(x - 0.02f, h * 0.6f, zq * 1.1f)),
                             Vec3Track(glm::vec3(x - 0.06f, h, zq * 1.2f))};
        BlobNode quill = b.pointSpline("quill_" + std::to_string(row) + "_" + std::to_string(q), std::move(pts), 5.0f,
                                       0.075f, 0.04f, 0.9f, "");
        back.children.push_back(std::move(quill));
      }
  } else {
    back.children.push_back(buildWing(b, s, "l"));
    back.children.push_back(buildWing(b, s, "r"));
  }
  return back;
}

// The neck, the head on it and the jaw: the dinosaur's teeth, the dragon's horns.
BlobNode buildNeck(Builder& b, const BodyStyle& s) {
  const double loop = s.loopSec, w = kTwoPi / loop;
  BlobNode neck = b.frame("neck", {0.62f, 0.16f, 0});
  neck.quatParam("rotation") = rotationLoop(loop, {0, 0, 1}, [=](double t) {
    return (s.dragon ? 0.1f : -0.05f) + 0.06f * float(std::sin(w * t + 0.7));
  });
  float nl = s.neckLength;
  glm::vec3 neckEnd(0.8f * nl, 1.0f * nl, 0);
  neck.children.push_back(b.part("neckflesh", {{-0.05f, -0.02f, 0}, 0.5f * neckEnd + glm::vec3(0.04f, 0, 0), neckEnd},
                                  {0.22f, 0.18f, 0.15f}));
  BlobNode head = b.frame("head", neckEnd);
  head.quatParam("rotation") = rotationLoop(loop, {0, 0, 1}, [=](double t) {
    return -0.15f - 0.08f * float(std::sin(w * t + 1.4));
  });
  head.children.push_back(b.part("skull", {{-0.06f, 0.04f, 0}, {0.2f, 0.02f, 0}, {0.45f, -0.04f, 0}}, {0.17f, 0.14f, 0.08f}));
  BlobNode jaw = b.frame("jaw", {-0.02f, -0.08f, 0});
  jaw.quatParam("rotation") = rotationLoop(loop, {0, 0, 1}, [=](double t) {
    return -0.12f - 0.1f * float(0.5 + 0.5 * std::sin(2.0 * w * t));
  });
  jaw.children.push_back(b.part("jawflesh", {{-0.02f, 0, 0}, {0.2f, -0.04f, 0}, {0.42f, -0.04f, 0}}, {0.1f, 0.08f, 0.05f}));
  if (!s.dragon)
    for (int side = -1; side <= 1; side += 2)
      for (int k = 0; k < 8; ++k) {
        float x = 0.1f + 0.04f * float(k), zt = float(side) * (0.055f - 0.004f * float(k));
        std::string n = std::string(side < 0 ? "r" : "l") + std::to_string(k);
        head.children.push_back(b.cone("tooth_" + n, {x, -0.09f, zt}, {x + 0.01f, -0.16f, zt}, 0.014f, 0.003f, 0.03f));
        jaw.children.push_back(b.cone("lowtooth_" + n, {x, 0.0f, zt}, {x + 0.01f, 0.06f, zt}, 0.012f, 0.003f, 0.03f));
      }
  else
    for (int side = -1; side <= 1; side += 2)
      head.children.push_back(b.part(std::string("horn_") + (side < 0 ? "r" : "l"),
                                      {{-0.02f, 0.12f, 0.07f * side}, {-0.16f, 0.2f, 0.1f * side}, {-0.3f, 0.24f, 0.12f * side}},
                                      {0.05f, 0.038f, 0.025f}, &kBoneLayers));
  head.children.push_back(std::move(jaw));
  neck.children.push_back(std::move(head));
  return neck;
}

BlobNode buildTail(Builder& b, const BodyStyle& s) {
  const double loop = s.loopSec, w = kTwoPi / loop;
  // The tail: fibres whose control points sway sideways, the wave running to the tip.
  BlobNode tailFrame = b.frame("tail", {-0.4f, 0.04f, 0});
  float tl = s.tailLength;
  PartSpec tail;
  tail.name = "tailflesh";
  tail.axis = {{0.05f, 0, 0}, {-0.25f * tl, 0.02f, 0}, {-0.5f * tl, -0.02f, 0}, {-0.75f * tl, 0.0f, 0}, {-tl, 0.06f, 0}};
  tail.radii = {0.27f, 0.2f, 0.14f, 0.09f, 0.055f};
  tail.loopSec = loop;
  float amp = s.dragon ? 0.18f : 0.12f;
  tail.sway = [=](int j, double t) {
    float reach = float(j) / 4.0f;
    return glm::vec3(0, s.dragon ? 0.05f * reach * float(std::sin(w * t - 1.2 * j)) : 0.0f,
                     amp * reach * reach * 2.0f * float(std::sin(w * t - 0.9 * j)));
  };
  tailFrame.children.push_back(b.part(tail));
  return tailFrame;
}

BlobTree buildCreature(const BodyStyle& s) {
  Builder b;
  BlobTree tree;
  tree.threshold = FloatTrack(kThreshold);
  tree.root = b.node(NodeType::Blend, s.dragon ? "dragon" : "dinosaur");
  const double loop = s.loopSec, w = kTwoPi / loop;

  // The creature's height above the ground (the dragon flies, rising on each downstroke).
  BlobNode flight = b.frame("flight", {0, 0, 0});
  if (s.dragon)
    flight.vec3Param("translation") = loopTrack<glm::vec3>(loop, 8, [=](double t) {
      return glm::vec3(0, 1.3f + 0.08f * float(std::sin(w * t - 1.0)), 0);
    });

  BlobNode pelvis = b.frame("pelvis", {0, 1.52f, 0});
  pelvis.vec3Param("translation") = loopTrack<glm::vec3>(loop, 8, [=](double t) {
    return glm::vec3(0, 1.52f + (s.dragon ? 0.0f : 0.035f * float(std::cos(2.0 * w * t))), 0);
  });
  pelvis.quatParam("rotation") = rotationLoop(loop, {1, 0, 0}, [=](double t) {
    return (s.dragon ? 0.02f : 0.05f) * float(std::sin(w * t));
  });
  float g = s.girth;
  pelvis.children.push_back(b.part("hips", {{-0.4f, 0.02f, 0}, {-0.05f, 0.05f, 0}, {0.25f, 0.1f, 0}},
                                    {0.26f * g, 0.33f * g, 0.34f * g}));
  PartSpec belly;
  belly.name = "belly";
  belly.axis = {{-0.15f, -0.12f, 0}, {0.15f, -0.14f, 0}, {0.45f, -0.08f, 0}};
  belly.radii = {0.2f * g, 0.24f * g, 0.2f * g};
  belly.loopSec = loop;
  belly.breath = s.dragon ? 0.04f : 0.08f;
  pelvis.children.push_back(b.part(belly));

  BlobNode chest = b.frame("chest", {0.3f, 0.1f, 0});
  chest.quatParam("rotation") = rotationLoop(loop, {0, 1, 0}, [=](double t) {
    return (s.dragon ? 0.02f : 0.06f) * float(std::sin(w * t));
  });
  chest.children.push_back(b.part("torso", {{-0.1f, 0, 0}, {0.25f, 0.06f, 0}, {0.6f, 0.16f, 0}}, {0.34f * g, 0.33f * g, 0.24f * g}));

  chest.children.push_back(buildBack(b, s));

  chest.children.push_back(buildNeck(b, s));
  chest.children.push_back(buildArm(b, s, "l", 0.2f, 0.0f));
  chest.children.push_back(buildArm(b, s, "r", -0.2f, 3.14159265f));
  pelvis.children.push_back(std::move(chest));

  pelvis.children.push_back(buildLeg(b, s, "l", 0.22f, 0.0f));
  pelvis.children.push_back(buildLeg(b, s, "r", -0.22f, 3.14159265f));

  pelvis.children.push_back(buildTail(b, s));

  flight.children.push_back(std::move(pelvis));
  tree.root.children.push_back(std::move(flight));
  paint(tree.root, s.dragon ? kDragonColors : kDinosaurColors, "");
  roundValues(tree.root);
  return tree;
}

void collectNames(const BlobNode& n, std::map<std::string, int>& out) {
  if (!n.name.empty()) out.emplace(n.name, n.id);
  for (const auto& c : n.children) collectNames(c, out);
}

// Links every named node of `a` below the root to the node of `b` of the same
// name, parents before children.
void linkByName(const BlobNode& a, const std::map<std::string, int>& bNames, CorrespondenceGraph& g, bool isRoot) {
  if (!isRoot && !a.name.empty()) {
    auto it = bNames.find(a.name);
    if (it == bNames.end()) return;  // unlinked: so is everything below it
    CorrespondenceLink l;
    l.nodeA = a.id;
    l.nodeB = it->second;
    g.links.push_back(l);
  }
  for (const auto& c : a.children) linkByName(c, bNames, g, false);
}

}  // namespace

BlobTree makeDinosaur() { return buildCreature({false, kDinosaurLoopSec, 0.32f, 1.9f, 1.0f}); }

BlobTree makeDragon() { return buildCreature({true, kDragonLoopSec, 0.45f, 2.3f, 0.85f}); }

CorrespondenceGraph dinosaurToDragonGraph(const BlobTree& dinosaur, const BlobTree& dragon) {
  std::map<std::string, int> dragonNames;
  collectNames(dragon.root, dragonNames);
  CorrespondenceGraph g;
  linkByName(dinosaur.root, dragonNames, g, true);
  std::map<std::string, int> dinoNames;
  collectNames(dinosaur.root, dinoNames);
  auto overrideOf = [&](const std::string& name, FloatTrack s) {
    int index = g.find(dinoNames.at(name), dragonNames.at(name));
    if (index >= 0) g.links[size_t(index)].sOverride = std::move(s);
  };
  // Held at the ground for the first third, then a smooth rise.
  FloatTrack height;
  height.clearKeys();
  for (auto [u, v] : {std::pair{0.0, 0.0f}, {1.0 / 3.0, 0.0f}, {1.0, 1.0f}}) {
    TrackKey<float> k;
    k.timeSec = u;
    k.value = v;
    k.userDerivatives = true;
    height.setKey(k);
  }
  overrideOf("flight", height);
  overrideOf("pelvis", defaultSCurve());
  overrideOf("back", hermiteRampTrack(2.5f, 0.0f));
  overrideOf("hip_l", hermiteRampTrack(2.0f, 0.0f));
  overrideOf("hip_r", hermiteRampTrack(2.0f, 0.0f));
  return g;
}

}  // namespace animorph
