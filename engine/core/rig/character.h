#pragma once
// An imported character: node hierarchy, meshes, skins, animation clips and
// materials, as glTF describes them (io/gltf_import.h fills it from glTF,
// io/assimp_import.h from FBX, Collada and OBJ; io/character_import.h picks).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/math/bounds.h"
#include "core/math/transform.h"
#include "core/rig/texture_image.h"

namespace animorph {

struct Node {
  std::string name;
  int parent = -1;
  std::vector<int> children;
  Transform rest;  // local transform when no animation drives it
  int mesh = -1;   // index into Character::meshes, or -1
  int skin = -1;   // index into Character::skins, or -1
};

// One blend shape (a glTF morph target) of a Mesh: per-vertex offsets added to
// the bind-space positions (and normals) before skinning, scaled by the target's
// weight: p = p0 + sum_t w_t * positionDeltas_t, n = normalize(n0 + sum_t w_t * normalDeltas_t).
struct MorphTarget {
  std::string name;                       // glTF mesh.extras.targetNames[t], else "target t"
  std::vector<glm::vec3> positionDeltas;  // one per vertex of the mesh
  std::vector<glm::vec3> normalDeltas;    // one per vertex of the mesh; empty: the target moves no normal
};

// Triangle geometry of one glTF mesh (its triangle primitives concatenated).
// Up to kMaxInfluences joint influences per vertex, in two sets of four
// (JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1); weights sum to 1. A mesh
// without a skin has every vertex bound to joint 0 with weight 1, and the
// renderer binds joint 0 to the node's own matrix.
struct Mesh {
  static constexpr int kMaxInfluences = 8;
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<uint32_t> indices;  // triangle list
  std::vector<glm::uvec4> joints0, joints1;
  std::vector<glm::vec4> weights0, weights1;
  std::vector<glm::vec4> colors;  // glTF COLOR_0 (RGBA, 0..1; RGB files get alpha 1); empty: none
  // Texture coordinates of the base colour texture, one per vertex: glTF TEXCOORD_n of the
  // material's baseColorTexture (n = its texCoord, usually 0) with the material's
  // KHR_texture_transform already applied; (0, 0) is the image's top-left corner. Empty: none.
  std::vector<glm::vec2> texcoords0;
  int material = -1;              // index into Character::materials (its first primitive's), or -1
  // The triangles of each material, in index order (one part per glTF primitive, FBX / Collada
  // material group). Empty: the whole mesh is drawn with `material`. A part whose range does
  // not lie inside `indices` is ignored by the renderer.
  struct Part {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = -1;  // index into Character::materials, or -1 (the default material)
  };
  std::vector<Part> parts;
  // Blend shapes. A glTF mesh's primitives are concatenated, and so are their
  // targets: target t holds primitive k's target t at primitive k's vertices
  // (zero deltas where a primitive has fewer targets). defaultMorphWeights has
  // one weight per target (glTF mesh.weights, else zeros): what the mesh shows
  // when no animation drives its node's weights.
  std::vector<MorphTarget> morphTargets;
  std::vector<float> defaultMorphWeights;

  size_t vertexCount() const { return positions.size(); }
  size_t triangleCount() const { return indices.size() / 3; }
  Bounds bounds() const;
};

struct Skin {
  std::string name;
  std::vector<int> joints;  // node indices
  std::vector<glm::mat4> inverseBindMatrices;
  int skeletonRoot = -1;
};

enum class Interpolation { Step, Linear, CubicSpline };
// Weights: the morph target weights of the mesh the node draws (glTF "weights").
enum class ChannelPath { Translation, Rotation, Scale, Weights };

// One animated property of one node. For CubicSpline, values holds three
// entries per key: in-tangent, value, out-tangent (glTF layout). Vectors are
// stored in xyz, quaternions as (x, y, z, w).
// A Weights channel leaves values empty and keeps its keys in weightValues,
// weightCount (the number of morph targets of the node's mesh) floats per key:
// Step/Linear: key k's weights at [k * weightCount, (k + 1) * weightCount);
// CubicSpline: 3 * weightCount floats per key, as glTF orders them: the
// in-tangents of every target, then the values, then the out-tangents
// (a_1..a_T, v_1..v_T, b_1..b_T).
struct Channel {
  int node = -1;
  ChannelPath path = ChannelPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> timesSec;
  std::vector<glm::vec4> values;
  std::vector<float> weightValues;  // Weights only (see above)
  int weightCount = 0;              // Weights only: weights per key (morph targets of the node's mesh)
};

struct AnimationClip {
  std::string name;
  std::vector<Channel> channels;
  float durationSec = 0.0f;
};

// A surface's base colour, as the file gives it (glTF baseColorFactor / baseColorTexture,
// FBX / Collada / OBJ diffuse colour and texture). The renderer draws
// baseColorFactor x texture x COLOR_0 under the viewport lighting (docs/rendering.md).
struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};  // linear RGBA, 0..1
  // The base colour texture's file, relative to the character file's folder (never absolute,
  // never outside that folder: such URIs are dropped with a warning); empty: none, or embedded.
  std::string baseColorTextureUri;
  bool baseColorTextureEmbedded = false;  // the texture is inside the file (decoded like a file's)
  // The decoded base colour texture: index into Character::textures; -1: none, or it could not
  // be decoded (the import report's warning names it and the reason; the factor colour is drawn).
  int baseColorTexture = -1;
};

// The length unit of the file's scene units. Geometry stays in the file's units; morphs and
// exports scale by metresPerUnit where two characters meet.
struct LengthUnit {
  double metresPerUnit = 1.0;
  std::string name = "metres";  // "centimetres", "inches", "units of 0.5 m" ...
  bool declared = true;         // false: the format says nothing (OBJ), metres assumed
};

// What the importer did that the user should know about.
struct ImportReport {
  std::vector<std::string> warnings;     // recoverable problems, one line each
  std::vector<std::string> unsupported;  // glTF features present but not used, by name
  size_t weightsNormalised = 0;          // vertices whose weights did not sum to 1
  size_t influencesDropped = 0;          // vertices with more than kMaxInfluences non-zero weights
  size_t normalsComputed = 0;            // meshes whose normals were computed
  double importMs = 0.0;
};

struct Character {
  std::string sourcePath;
  std::vector<Node> nodes;
  std::vector<int> roots;  // nodes of the scene, in order
  std::vector<Mesh> meshes;
  std::vector<Skin> skins;
  std::vector<AnimationClip> clips;
  std::vector<Material> materials;
  std::vector<TextureImage> textures;  // decoded base colour textures (Material::baseColorTexture)
  LengthUnit unit;      // glTF: metres
  std::string format;   // "glTF", "FBX", "Collada", "OBJ"
  ImportReport report;

  size_t totalVertices() const;
  size_t totalTriangles() const;
  size_t totalJoints() const;  // distinct joint nodes over all skins
  // Nodes that draw a mesh, in hierarchy order.
  std::vector<int> meshNodes() const;
};

}  // namespace animorph
