#include "demo/rigged_figure.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "demo/rig_builder.h"
#include "core/field/skeleton.h"
#include "core/poly/polygonizer.h"
#include "core/standin/standin.h"

namespace animorph {

namespace {

struct Bone {
  std::string name;
  int parent;
  glm::vec3 joint;     // figure space (metres, Y up, 1.8 tall)
  bool helper = false; // no vertices of its own
  float scale = 1.0f;  // node scale
  // Body capsule drawn for the bone (radius 0: none) and the capsule its
  // vertices are weighted by (face bones weigh without drawing).
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.0f;
  bool draws = true;
};

// Adds bones: a drawn one (a body capsule from joint to tail) or a helper (no vertices).
struct BoneList {
  std::vector<Bone> bones;
  int add(const std::string& name, int parent, glm::vec3 joint, glm::vec3 tail, float radius) {
    bones.push_back({name, parent, joint, false, 1.0f, joint, tail, radius, true});
    return int(bones.size()) - 1;
  }
  int helper(const std::string& name, int parent, glm::vec3 joint) {
    bones.push_back({name, parent, joint, true, 1.0f, joint, joint, 0.0f, false});
    return int(bones.size()) - 1;
  }
};

// The head's face bones: weighted, not drawn.
void addFaceBones(BoneList& l, int head) {
  const char* face[] = {"Jaw", "Eye_L", "Eye_R", "Brow_L", "Brow_R", "Cheek_L", "Cheek_R", "Nose", "Lip_U", "Lip_D"};
  const glm::vec3 facePos[] = {{0, 1.6f, 0.07f},     {0.035f, 1.68f, 0.085f}, {-0.035f, 1.68f, 0.085f},
                               {0.035f, 1.72f, 0.08f}, {-0.035f, 1.72f, 0.08f}, {0.06f, 1.64f, 0.07f},
                               {-0.06f, 1.64f, 0.07f}, {0, 1.66f, 0.1f},        {0, 1.62f, 0.095f},
                               {0, 1.6f, 0.09f}};
  for (int k = 0; k < 10; ++k) {
    const int f = l.add(face[k], head, facePos[k], facePos[k], 0.03f);
    l.bones[size_t(f)].draws = false;
  }
}

// One side's (x = -1: right, 1: left) shoulder, arm, hand with four three-bone fingers, and leg.
void addLimbs(BoneList& l, int chest, int hips, int side, bool h) {
  const std::string s = side < 0 ? "_R" : "_L";
  const float x = float(side);
  const int shoulder = l.add("Shoulder" + s, chest, {0.06f * x, 1.45f, 0}, {0.18f * x, 1.45f, 0}, 0.06f);
  int arm = l.add("UpperArm" + s, shoulder, {0.18f * x, 1.45f, 0}, {0.45f * x, 1.45f, 0}, 0.05f);
  if (h) arm = l.helper("UpperArmTwist" + s, arm, {0.32f * x, 1.45f, 0});
  int fore = l.add("ForeArm" + s, arm, {0.45f * x, 1.45f, 0}, {0.7f * x, 1.45f, 0}, 0.04f);
  if (h) fore = l.helper("ForeArmTwist" + s, fore, {0.58f * x, 1.45f, 0});
  const int hand = l.add("Hand" + s, fore, {0.7f * x, 1.45f, 0}, {0.78f * x, 1.45f, 0}, 0.035f);
  for (int f = 0; f < 4; ++f) {
    const float z = -0.052f + 0.035f * float(f);
    int prev = hand;
    float x0 = 0.79f;
    for (int k = 1; k <= 3; ++k) {
      const float x1 = x0 + 0.03f;
      prev = l.add("Finger" + std::to_string(f + 1) + "_" + std::to_string(k) + s, prev, {x0 * x, 1.45f, z},
                   {x1 * x, 1.45f, z}, 0.012f);
      x0 = x1;
    }
    if (h) l.helper("Finger" + std::to_string(f + 1) + "_End" + s, prev, {x0 * x, 1.45f, z});
  }
  const int up = l.add("UpLeg" + s, hips, {0.1f * x, 0.95f, 0}, {0.1f * x, 0.5f, 0}, 0.07f);
  const int leg = l.add("Leg" + s, up, {0.1f * x, 0.5f, 0}, {0.1f * x, 0.08f, 0}, 0.055f);
  const int foot = l.add("Foot" + s, leg, {0.1f * x, 0.08f, 0}, {0.1f * x, 0.04f, 0.12f}, 0.045f);
  const int toe = l.add("Toe" + s, foot, {0.1f * x, 0.04f, 0.12f}, {0.1f * x, 0.04f, 0.2f}, 0.035f);
  if (h) l.helper("Toe_End" + s, toe, {0.1f * x, 0.04f, 0.22f});
}

// The figure's bones in figure space (metres, Y up, 1.8 tall), helpers where the options ask.
std::vector<Bone> figureBones(const RiggedFigureOptions& o) {
  BoneList l;
  const bool h = o.helperBones;
  const int hips = l.add("Hips", -1, {0, 1.0f, 0}, {0, 1.12f, 0}, 0.14f);
  if (h) l.helper("IK_pole_target", hips, {0.5f, 1.0f, -0.6f});
  int spine = hips;
  if (h) spine = l.helper("SpineTwist1", spine, {0, 1.12f, 0});
  if (h) spine = l.helper("SpineTwist2", spine, {0, 1.22f, 0});
  const int chest = l.add("Chest", spine, {0, 1.3f, 0}, {0, 1.45f, 0}, 0.15f);
  if (o.chestScale) l.bones[size_t(chest)].scale = 1.5f;
  // Hips' body reaches the chest even when twist bones stand between.
  l.bones[size_t(hips)].b = {0, 1.3f, 0};
  const int neck = l.add("Neck", chest, {0, 1.52f, 0}, {0, 1.58f, 0}, 0.05f);
  const int head = l.add("Head", neck, {0, 1.58f, 0}, {0, 1.72f, 0}, 0.1f);
  if (h) l.helper("HeadTop_End", head, {0, 1.85f, 0});
  addFaceBones(l, head);
  for (int side = -1; side <= 1; side += 2) addLimbs(l, chest, hips, side, h);
  return std::move(l.bones);
}

// The body: one union of the drawn bones' capsules, polygonised (figure space), skinned to the two
// bones whose capsules' surfaces are nearest each vertex.
Mesh figureBody(const std::vector<Bone>& bones, int resolution) {
  std::vector<PosedSegment> body;
  for (const Bone& b : bones)
    if (b.draws && b.radius > 0.0f) body.push_back({b.a, b.b, b.radius, 1.0f});
  PolygonizeSettings ps;
  ps.resolution = resolution;
  ps.bounds = posedStandinBounds(body, 0.02f);
  auto poly = polygonize(standinProgram(StandinKind::CapsuleUnion, 1.0f, body), ps);
  Mesh mesh;
  mesh.name = "Body";
  if (poly) {
    mesh.positions = poly->mesh.positions;
    mesh.normals = poly->mesh.normals;
    mesh.indices = poly->mesh.indices;
  }
  const size_t nb = bones.size();
  mesh.joints0.resize(mesh.positions.size());
  mesh.weights0.resize(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    std::vector<float> w(nb, 0.0f);
    std::vector<std::pair<float, size_t>> d;
    for (size_t k = 0; k < nb; ++k) {
      if (bones[k].helper) continue;
      const float dist = glm::length(p - closestOnSegment(p, bones[k].a, bones[k].b)) - bones[k].radius;
      // Signed: a face bone's vertices lie inside its small capsule and win over the head's.
      d.push_back({dist, k});
    }
    std::partial_sort(d.begin(), d.begin() + 2, d.end());
    const float w0 = 1.0f / (std::max(d[0].first, 0.0f) + 1e-3f), w1 = 0.5f / (std::max(d[1].first, 0.0f) + 1e-3f);
    w[d[0].second] = w0;
    w[d[1].second] = w1;
    topFourInfluences(w, mesh.joints0[v], mesh.weights0[v]);
  }
  return mesh;
}

}  // namespace

Character makeRiggedFigure(const RiggedFigureOptions& o) {
  const std::vector<Bone> bones = figureBones(o);
  Mesh mesh = figureBody(bones, o.resolution);
  const size_t nb = bones.size();
  // Nodes: Armature (turned 90° about X, scale 0.01) -> bones; world = k * figure.
  const float k = o.height / 1.85f;
  Character c;
  c.sourcePath = "rigged_figure";
  Node arm;
  arm.name = "Armature";
  arm.rest.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(1, 0, 0));
  arm.rest.scale = glm::vec3(0.01f);
  c.nodes.push_back(arm);
  c.roots.push_back(0);
  const glm::mat4 A = arm.rest.matrix();
  const glm::mat4 invA = glm::inverse(A);
  std::vector<glm::mat4> global(nb);
  Skin skin;
  skin.name = "Armature";
  for (size_t b = 0; b < nb; ++b) {
    Node n;
    n.name = bones[b].name;
    const int parentNode = bones[b].parent < 0 ? 0 : 1 + bones[b].parent;
    const glm::mat4 pg = bones[b].parent < 0 ? A : global[size_t(bones[b].parent)];
    n.parent = parentNode;
    n.rest.translation = glm::vec3(glm::inverse(pg) * glm::vec4(k * bones[b].joint, 1.0f));
    n.rest.scale = glm::vec3(bones[b].scale);
    global[b] = pg * n.rest.matrix();
    c.nodes.push_back(n);
    c.nodes[size_t(parentNode)].children.push_back(int(b) + 1);
    skin.joints.push_back(int(b) + 1);
    // Vertices live in the armature's space.
    skin.inverseBindMatrices.push_back(glm::inverse(invA * global[b]));
  }
  skin.skeletonRoot = 1;
  for (auto& p : mesh.positions) p = glm::vec3(invA * glm::vec4(k * p, 1.0f));
  for (auto& n : mesh.normals) n = glm::normalize(glm::vec3(glm::transpose(A) * glm::vec4(n, 0.0f)));
  c.meshes.push_back(std::move(mesh));
  c.skins.push_back(skin);
  Node meshNode;
  meshNode.name = "Body";
  meshNode.mesh = 0;
  meshNode.skin = 0;
  meshNode.parent = 0;
  c.nodes.push_back(meshNode);
  c.nodes[0].children.push_back(int(c.nodes.size()) - 1);
  return c;
}

}  // namespace animorph
