// FBX, Collada and OBJ import with Debian's assimp (libassimp 5.2). The only file that
// includes assimp: it parses, this file checks every index and count before using it and
// converts to the Character model (the glTF conventions: +Y up, node TRS, joint matrices
// global(joint) * inverseBind, linear keys, quaternions (x, y, z, w)).
#include "core/io/assimp_import.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "core/io/collada_morph_weights.h"
#include "core/io/collada_morphs.h"
#include "core/io/declared_size_check.h"
#include "core/io/fbx_shape_values.h"
#include "core/io/texture_decode.h"
#include "core/rig/mesh_normals.h"
#include "core/rig/skin_influences.h"
#include "core/util/atomic_file.h"

namespace animorph {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return e;
}

bool isInside(const fs::path& p, const fs::path& dir) {
  auto d = dir.begin(), q = p.begin();
  for (; d != dir.end(); ++d, ++q)
    if (q == p.end() || *q != *d) return false;
  return true;
}

// ---------------------------------------------------------------------------
// File access: assimp opens the file and what it references (OBJ .mtl) through this; only
// regular files under the size cap inside the file's folder open, nothing is written.

class FolderIOSystem : public Assimp::DefaultIOSystem {
 public:
  FolderIOSystem(fs::path folder, size_t maxBytes) : folder_(std::move(folder)), maxBytes_(maxBytes) {}

  bool Exists(const char* file) const override { return allowed(file, false); }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::string(mode).find_first_of("wa+") != std::string::npos) return nullptr;
    if (!allowed(file, true)) return nullptr;
    return DefaultIOSystem::Open(file, mode);
  }

  std::vector<std::string> refused;  // one line per file not opened, and why

 private:
  bool allowed(const char* file, bool record) const {
    std::error_code ec;
    const fs::path full = fs::weakly_canonical(fs::absolute(fs::path(file), ec), ec);
    std::string why;
    if (ec || !isInside(full, folder_)) why = "outside the file's folder";
    else if (!fs::is_regular_file(full, ec)) why = fs::exists(full, ec) ? "not a regular file" : "";
    else if (fs::file_size(full, ec) > maxBytes_) why = "larger than " + std::to_string(maxBytes_) + " bytes";
    if (!why.empty() && record) {
      auto* self = const_cast<FolderIOSystem*>(this);
      self->refused.push_back("'" + std::string(file) + "': " + why + "; not read");
    }
    return why.empty() && !ec && fs::is_regular_file(full, ec);
  }

  fs::path folder_;
  size_t maxBytes_;
};

// ---------------------------------------------------------------------------
// Conversion context.

struct Ctx {
  const std::string& file;  // the path as given, for messages
  const aiScene& s;
  const AssimpImportLimits& limits;
  fs::path folder;  // canonical folder of the file
  Character& ch;
  std::map<std::string, int> nodeByName;  // first node of each name
  const ColladaMorphDocument* collada = nullptr;  // Collada: the shapes read beside assimp
  const FbxShapeValues* fbxShapeValues = nullptr;  // FBX: the channels' values read beside assimp
  // Collada: per mesh index, the morphs (index into collada->morphs) whose targets it holds and the
  // index of the first of them among the mesh's targets.
  std::map<size_t, std::vector<std::pair<size_t, size_t>>> colladaMorphsOfMesh;
};

Error err(const Ctx& c, const std::string& element, const std::string& reason) {
  return Error{c.file + ": " + element + ": " + reason};
}

std::string label(const char* kind, size_t i, const aiString& name) {
  const std::string n = name.C_Str();
  return std::string(kind) + " " + std::to_string(i) + (n.empty() ? "" : " '" + n + "'");
}

glm::mat4 toGlm(const aiMatrix4x4& a) {
  glm::mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = a[r][c];
  return m;
}

bool finite(const glm::mat4& m) {
  for (int k = 0; k < 16; ++k)
    if (!std::isfinite(m[k / 4][k % 4])) return false;
  return true;
}

// The largest difference between m and its T * R * S decomposition, relative to m's size.
float decompositionError(const glm::mat4& m, const Transform& t) {
  const glm::mat4 back = t.matrix();
  float largest = 1.0f, worst = 0.0f;
  for (int k = 0; k < 16; ++k) {
    largest = std::max(largest, std::abs(m[k / 4][k % 4]));
    worst = std::max(worst, std::abs(back[k / 4][k % 4] - m[k / 4][k % 4]));
  }
  return worst / largest;
}

Transform safeDecompose(const glm::mat4& m) {
  Transform d = decompose(m);
  if (!std::isfinite(d.rotation.w) || !std::isfinite(d.rotation.x) || !std::isfinite(d.rotation.y) ||
      !std::isfinite(d.rotation.z))
    d.rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);  // a zero axis: that axis is hidden anyway
  return d;
}

// ---------------------------------------------------------------------------
// Counts checked against the limits before anything is converted.

Status checkCounts(const Ctx& c) {
  const aiScene& s = c.s;
  size_t vertices = 0, triangles = 0, keys = 0, shapeVertices = 0;
  for (unsigned i = 0; i < s.mNumMeshes; ++i) {
    const aiMesh* m = s.mMeshes[i];
    if (!m) return err(c, "mesh " + std::to_string(i), "missing");
    vertices += m->mNumVertices;
    triangles += m->mNumFaces;
    shapeVertices += size_t(m->mNumAnimMeshes) * m->mNumVertices;
    if (m->mNumBones > c.limits.maxBonesPerMesh)
      return err(c, label("mesh", i, m->mName), std::to_string(m->mNumBones) + " bones, more than the limit of " +
                                                    std::to_string(c.limits.maxBonesPerMesh));
  }
  if (vertices > c.limits.maxVertices)
    return Error{c.file + ": " + std::to_string(vertices) + " vertices, more than the limit of " +
                 std::to_string(c.limits.maxVertices)};
  if (shapeVertices > c.limits.maxBlendShapeVertices)
    return Error{c.file + ": blend shapes of " + std::to_string(shapeVertices) + " vertices in all, more than the limit of " +
                 std::to_string(c.limits.maxBlendShapeVertices)};
  if (triangles > c.limits.maxTriangles)
    return Error{c.file + ": " + std::to_string(triangles) + " faces, more than the limit of " +
                 std::to_string(c.limits.maxTriangles)};
  for (unsigned a = 0; a < s.mNumAnimations; ++a)
    for (unsigned k = 0; s.mAnimations[a] && k < s.mAnimations[a]->mNumChannels; ++k) {
      const aiNodeAnim* na = s.mAnimations[a]->mChannels[k];
      if (na) keys += size_t(na->mNumPositionKeys) + na->mNumRotationKeys + na->mNumScalingKeys;
    }
  for (unsigned a = 0; a < s.mNumAnimations; ++a)
    for (unsigned k = 0; s.mAnimations[a] && k < s.mAnimations[a]->mNumMorphMeshChannels; ++k)
      if (const aiMeshMorphAnim* mm = s.mAnimations[a]->mMorphMeshChannels[k]) keys += mm->mNumKeys;
  if (keys > c.limits.maxAnimationKeys)
    return Error{c.file + ": " + std::to_string(keys) + " animation keys, more than the limit of " +
                 std::to_string(c.limits.maxAnimationKeys)};
  return {};
}

// ---------------------------------------------------------------------------
// Nodes: pre-order, parents first. A node with several meshes (assimp splits a mesh per
// material) keeps the first and gets one child node per further mesh.

Status readNodes(Ctx& c) {
  Character& ch = c.ch;
  std::vector<std::pair<const aiNode*, int>> stack{{c.s.mRootNode, -1}};
  while (!stack.empty()) {
    auto [an, parent] = stack.back();
    stack.pop_back();
    if (ch.nodes.size() >= c.limits.maxNodes)
      return Error{c.file + ": more than " + std::to_string(c.limits.maxNodes) + " nodes"};
    const int index = int(ch.nodes.size());
    Node node;
    node.name = an->mName.length ? an->mName.C_Str() : "node " + std::to_string(index);
    node.parent = parent;
    const glm::mat4 m = toGlm(an->mTransformation);
    if (!finite(m)) return err(c, "node '" + node.name + "'", "transform is not finite");
    node.rest = safeDecompose(m);
    if (decompositionError(m, node.rest) > 1e-3f)
      ch.report.warnings.push_back("node '" + node.name + "': matrix has shear; the nearest translation x rotation x "
                                   "scale is used");
    for (unsigned k = 0; k < an->mNumMeshes; ++k)
      if (an->mMeshes[k] >= c.s.mNumMeshes)
        return err(c, "node '" + node.name + "'", "mesh " + std::to_string(an->mMeshes[k]) + " does not exist (" +
                                                       std::to_string(c.s.mNumMeshes) + " meshes)");
    if (an->mNumMeshes > 0) node.mesh = int(an->mMeshes[0]);
    c.nodeByName.emplace(node.name, index);
    if (parent >= 0) ch.nodes[parent].children.push_back(index);
    ch.nodes.push_back(std::move(node));
    for (unsigned k = 1; k < an->mNumMeshes; ++k) {
      Node extra;
      extra.name = ch.nodes[index].name + " mesh " + std::to_string(k);
      extra.parent = index;
      extra.mesh = int(an->mMeshes[k]);
      ch.nodes[index].children.push_back(int(ch.nodes.size()));
      ch.nodes.push_back(std::move(extra));
    }
    for (unsigned k = an->mNumChildren; k-- > 0;)
      if (an->mChildren[k]) stack.push_back({an->mChildren[k], index});
  }
  ch.roots = {0};
  return {};
}

// ---------------------------------------------------------------------------
// Blend shapes. assimp's anim meshes hold each target's whole positions (and normals); the
// Character keeps deltas from the base mesh, as glTF does. Default weights: FBX's channel values
// (DeformPercent), which assimp 5.2 does not pass on (it reports 1 for every shape), are read from
// the file by io/fbx_shape_values and matched by name. Collada's <morph> controllers do not reach
// assimp 5.2 at all: io/collada_morphs reads them and tags each vertex with its position in the
// file (readColladaMorphTargets).

glm::vec3 toGlm(const aiVector3D& v) { return {v.x, v.y, v.z}; }
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A shape's weight at rest: an FBX channel's value (DeformPercent / 100) matched by the shape's
// name, a Collada weight assimp gives; 0 when the file gives none (counted in missing).
float restWeight(const Ctx& c, const aiAnimMesh& a, size_t& missing) {
  if (c.ch.format == "Collada" && std::isfinite(a.mWeight)) return a.mWeight;
  if (c.fbxShapeValues) {
    auto it = c.fbxShapeValues->percentByChannel.find(a.mName.C_Str());
    if (it != c.fbxShapeValues->percentByChannel.end()) return float(it->second / 100.0);
  }
  ++missing;
  return 0.0f;
}

Status readMorphTargets(Ctx& c, const aiMesh& am, const std::string& name, Mesh& mesh) {
  const size_t nv = am.mNumVertices;
  size_t missing = 0;
  for (unsigned k = 0; k < am.mNumAnimMeshes; ++k) {
    const aiAnimMesh* a = am.mAnimMeshes[k];
    const std::string where = name + " blend shape " + std::to_string(k);
    if (!a) return err(c, where, "missing");
    if (a->mNumVertices != nv)
      return err(c, where, std::to_string(a->mNumVertices) + " vertices, the mesh has " + std::to_string(nv));
    MorphTarget t;
    t.name = a->mName.length ? a->mName.C_Str() : "target " + std::to_string(k);
    t.positionDeltas.assign(nv, glm::vec3(0.0f));
    for (size_t v = 0; a->mVertices && v < nv; ++v) {
      t.positionDeltas[v] = toGlm(a->mVertices[v]) - toGlm(am.mVertices[v]);
      if (!finite(t.positionDeltas[v]))
        return err(c, where, "position " + std::to_string(v) + " is not finite");
    }
    if (a->mNormals && am.mNormals && !mesh.normals.empty()) {
      t.normalDeltas.resize(nv);
      for (size_t v = 0; v < nv; ++v) {
        const glm::vec3 d = toGlm(a->mNormals[v]) - toGlm(am.mNormals[v]);
        t.normalDeltas[v] = finite(d) ? d : glm::vec3(0.0f);
      }
    }
    mesh.morphTargets.push_back(std::move(t));
    mesh.defaultMorphWeights.push_back(restWeight(c, *a, missing));
  }
  if (missing > 0)
    c.ch.report.warnings.push_back(name + ": " + std::to_string(missing) +
                                   " blend shapes have no value in the file's blend shape channels; they start at "
                                   "weight 0 where not animated");
  return {};
}

// The texture coordinate set of a mesh assimp built from a geometry io/collada_morphs tagged: the
// last set, whose second coordinate is kColladaIndexTag at every vertex; -1 when there is none.
int colladaTagSet(const aiMesh& am) {
  int last = -1;
  for (int s = 0; s < AI_MAX_NUMBER_OF_TEXTURECOORDS; ++s)
    if (am.mTextureCoords[s]) last = s;
  if (last < 0) return -1;
  for (unsigned v = 0; v < am.mNumVertices; ++v)
    if (am.mTextureCoords[last][v].y != kColladaIndexTag) return -1;
  return last;
}

// The Collada shapes of the geometry assimp built this mesh from (assimp names a mesh by its
// geometry's id): each vertex's tag is its position in the file, whose deltas it takes. Where the
// tags do not lead back to the vertices' positions, the shapes are dropped and the report says so.
void readColladaMorphTargets(Ctx& c, const aiMesh& am, int tagSet, const std::string& name, Mesh& mesh) {
  if (!c.collada || tagSet < 0) return;
  for (const ColladaMorph& morph : c.collada->morphs) {
    if (morph.baseGeometryId != am.mName.C_Str()) continue;
    std::vector<size_t> position(am.mNumVertices);
    for (unsigned v = 0; v < am.mNumVertices; ++v) {
      const float x = am.mTextureCoords[tagSet][v].x;
      const size_t i = x >= 0.0f ? size_t(x) : 0;
      const bool known = x >= 0.0f && float(i) == x && i < morph.basePositions.size();
      const glm::vec3 base = known ? morph.basePositions[i] : glm::vec3(0.0f);
      if (!known || glm::length(toGlm(am.mVertices[v]) - base) > 1e-4f * (1.0f + glm::length(base))) {
        c.ch.report.warnings.push_back(name + ": the blend shapes of controller '" + morph.controllerId +
                                       "' do not map onto the mesh's vertices (vertex " + std::to_string(v) +
                                       "); not read");
        return;
      }
      position[v] = i;
    }
    c.colladaMorphsOfMesh[c.ch.meshes.size()].push_back(
        {size_t(&morph - c.collada->morphs.data()), mesh.morphTargets.size()});
    for (size_t k = 0; k < morph.targets.size(); ++k) {
      MorphTarget t;
      t.name = morph.targets[k].name;
      t.positionDeltas.resize(am.mNumVertices);
      for (unsigned v = 0; v < am.mNumVertices; ++v) t.positionDeltas[v] = morph.targets[k].deltas[position[v]];
      mesh.morphTargets.push_back(std::move(t));
      mesh.defaultMorphWeights.push_back(morph.defaultWeights[k]);
    }
  }
}

// The node that draws the mesh a morph channel names: "NODE*K" (assimp's FBX converter: the
// node's K-th mesh), else a node or mesh name. -1: none.
int morphChannelNode(const Ctx& c, const std::string& channel) {
  std::string node = channel;
  std::string k = "0";
  if (const size_t star = channel.rfind('*'); star != std::string::npos && star + 1 < channel.size() &&
                                              channel.find_first_not_of("0123456789", star + 1) == std::string::npos)
    node = channel.substr(0, star), k = channel.substr(star + 1);
  if (auto it = c.nodeByName.find(node); it != c.nodeByName.end()) {
    if (k == "0") return it->second;
    for (int child : c.ch.nodes[size_t(it->second)].children)
      if (c.ch.nodes[size_t(child)].name == node + " mesh " + k) return child;
  }
  for (size_t i = 0; i < c.ch.nodes.size(); ++i) {
    const int m = c.ch.nodes[i].mesh;
    if (m >= 0 && c.ch.meshes[size_t(m)].name == channel) return int(i);
  }
  return -1;
}

// A target's weight at t from its own keys (time, weight), held before the first and after the
// last; def when the target has none.
float weightAt(const std::vector<std::pair<float, float>>& keys, float t, float def) {
  if (keys.empty()) return def;
  if (t <= keys.front().first) return keys.front().second;
  if (t >= keys.back().first) return keys.back().second;
  auto hi = std::upper_bound(keys.begin(), keys.end(), t, [](float x, const auto& k) { return x < k.first; });
  auto lo = hi - 1;
  const float u = hi->first > lo->first ? (t - lo->first) / (hi->first - lo->first) : 1.0f;
  return lo->second + u * (hi->second - lo->second);
}

// One mesh's weight animation as a Weights channel. A key lists only the targets keyed at its
// time; the others are interpolated from their own keys, so every key holds every weight.
Status readMorphChannel(Ctx& c, const std::string& clipWhere, const aiMeshMorphAnim& mm, double tps,
                        AnimationClip& clip) {
  const std::string where = clipWhere + " blend shape channel '" + std::string(mm.mName.C_Str()) + "'";
  const int node = morphChannelNode(c, mm.mName.C_Str());
  const int meshIndex = node < 0 ? -1 : c.ch.nodes[size_t(node)].mesh;
  const size_t targets = meshIndex < 0 ? 0 : c.ch.meshes[size_t(meshIndex)].morphTargets.size();
  if (targets == 0) {
    c.ch.report.warnings.push_back(where + ": names no mesh with blend shapes; skipped");
    return {};
  }
  Channel out;
  out.node = node;
  out.path = ChannelPath::Weights;
  out.weightCount = int(targets);
  std::vector<std::vector<std::pair<float, float>>> own(targets);
  for (unsigned k = 0; k < mm.mNumKeys; ++k) {
    const aiMeshMorphKey& key = mm.mKeys[k];
    const double t = key.mTime / tps;
    if (!std::isfinite(t)) return err(c, where, "key " + std::to_string(k) + ": time is not finite");
    if (k > 0 && float(t) < out.timesSec.back()) return err(c, where, "key times decrease at key " + std::to_string(k));
    if (key.mNumValuesAndWeights > 0 && (!key.mValues || !key.mWeights))
      return err(c, where, "key " + std::to_string(k) + ": no values");
    for (unsigned q = 0; q < key.mNumValuesAndWeights; ++q) {
      if (key.mValues[q] >= targets)
        return err(c, where, "key " + std::to_string(k) + ": blend shape " + std::to_string(key.mValues[q]) +
                                 " does not exist (" + std::to_string(targets) + ")");
      if (!std::isfinite(key.mWeights[q])) return err(c, where, "key " + std::to_string(k) + ": weight is not finite");
      own[key.mValues[q]].push_back({float(t), float(key.mWeights[q])});
    }
    out.timesSec.push_back(float(t));
  }
  if (out.timesSec.empty()) return {};
  const std::vector<float>& defaults = c.ch.meshes[size_t(meshIndex)].defaultMorphWeights;
  for (float t : out.timesSec)
    for (size_t i = 0; i < targets; ++i) out.weightValues.push_back(weightAt(own[i], t, defaults[i]));
  clip.durationSec = std::max(clip.durationSec, out.timesSec.back());
  clip.channels.push_back(std::move(out));
  return {};
}

// Collada morph weight animation (io/collada_morph_weights): a Weights channel on every node that
// draws a mesh holding an animated morph's targets, in the first clip (one made when there is none).
void addColladaWeightChannels(Ctx& c) {
  if (!c.collada) return;
  for (const std::string& n : c.collada->notes) c.ch.report.warnings.push_back(n);
  for (const auto& [meshIndex, parts] : c.colladaMorphsOfMesh) {
    std::vector<float> times;
    bool step = true;
    for (const auto& [morph, offset] : parts) {
      const ColladaMorph& m = c.collada->morphs[morph];
      times.insert(times.end(), m.weightTimesSec.begin(), m.weightTimesSec.end());
      step = step && (m.weightTimesSec.empty() || m.weightsStep);
    }
    if (times.empty()) continue;
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    const Mesh& mesh = c.ch.meshes[meshIndex];
    const size_t n = mesh.morphTargets.size();
    Channel out;
    out.path = ChannelPath::Weights;
    out.interpolation = step ? Interpolation::Step : Interpolation::Linear;
    out.weightCount = int(n);
    out.weightValues.resize(times.size() * n);
    for (size_t i = 0; i < times.size(); ++i) {
      std::copy(mesh.defaultMorphWeights.begin(), mesh.defaultMorphWeights.end(), out.weightValues.begin() + i * n);
      for (const auto& [morph, offset] : parts)
        for (size_t k = 0; k < c.collada->morphs[morph].targets.size() && offset + k < n; ++k)
          out.weightValues[i * n + offset + k] = colladaMorphWeightAt(c.collada->morphs[morph], k, times[i]);
    }
    out.timesSec = std::move(times);
    if (c.ch.clips.empty()) c.ch.clips.push_back(AnimationClip{"animation 0", {}, 0.0f});
    AnimationClip& clip = c.ch.clips.front();
    for (size_t node = 0; node < c.ch.nodes.size(); ++node) {
      if (c.ch.nodes[node].mesh != int(meshIndex)) continue;
      out.node = int(node);
      clip.channels.push_back(out);
      clip.durationSec = std::max(clip.durationSec, out.timesSec.back());
    }
  }
}

// ---------------------------------------------------------------------------
// Meshes and skins.

// The mesh's skin: one per mesh with bones, its joints the nodes the bones name; the
// influences packed as glTF's are (8 strongest, normalised). skinOut: the skin's index or -1.
Status readSkin(Ctx& c, const aiMesh& am, const std::string& name, Mesh& mesh, int& skinOut) {
  const size_t nv = am.mNumVertices;
  std::vector<std::vector<Influence>> influences(am.mNumBones > 0 ? nv : 0);
  Skin skin;
  skin.name = mesh.name + " skin";
  for (unsigned b = 0; b < am.mNumBones; ++b) {
    const aiBone* bone = am.mBones[b];
    if (!bone) return err(c, name, "bone " + std::to_string(b) + " is missing");
    const std::string boneName = bone->mName.C_Str();
    auto node = c.nodeByName.find(boneName);
    if (node == c.nodeByName.end()) return err(c, name, "bone '" + boneName + "' names no node");
    const glm::mat4 ibm = toGlm(bone->mOffsetMatrix);
    if (!finite(ibm)) return err(c, name, "bone '" + boneName + "': offset matrix is not finite");
    skin.joints.push_back(node->second);
    skin.inverseBindMatrices.push_back(ibm);
    for (unsigned w = 0; w < bone->mNumWeights; ++w) {
      const aiVertexWeight& vw = bone->mWeights[w];
      if (vw.mVertexId >= nv)
        return err(c, name, "bone '" + boneName + "': weight " + std::to_string(w) + " names vertex " +
                                std::to_string(vw.mVertexId) + " (" + std::to_string(nv) + " vertices)");
      if (std::isfinite(vw.mWeight) && vw.mWeight > 0.0f) influences[vw.mVertexId].push_back({b, vw.mWeight});
    }
  }
  if (am.mNumBones == 0) {
    mesh.joints0.assign(nv, glm::uvec4(0));
    mesh.weights0.assign(nv, glm::vec4(1, 0, 0, 0));
    skinOut = -1;
  } else {
    InfluenceStats stats;
    mesh.joints0.resize(nv);
    mesh.weights0.resize(nv);
    mesh.joints1.resize(nv);
    mesh.weights1.resize(nv);
    bool second = false;
    for (size_t v = 0; v < nv; ++v) {
      packInfluences(influences[v], mesh.joints0[v], mesh.weights0[v], mesh.joints1[v], mesh.weights1[v], stats);
      second |= mesh.weights1[v].x > 0.0f;
    }
    if (!second) {
      mesh.joints1.clear();
      mesh.weights1.clear();
    }
    c.ch.report.weightsNormalised += stats.normalised;
    c.ch.report.influencesDropped += stats.dropped;
    if (stats.unweighted)
      c.ch.report.warnings.push_back(name + ": " + std::to_string(stats.unweighted) +
                                     " vertices have no skin weight; bound to the skin's first joint");
    if (stats.dropped)
      c.ch.report.warnings.push_back(name + ": " + std::to_string(stats.dropped) +
                                     " vertices have more than 8 influences; the smallest were dropped");
    skinOut = int(c.ch.skins.size());
    c.ch.skins.push_back(std::move(skin));
  }
  return {};
}

Result<Mesh> readMesh(Ctx& c, unsigned index, int& skinOut) {
  const aiMesh& am = *c.s.mMeshes[index];
  const std::string name = label("mesh", index, am.mName);
  Mesh mesh;
  mesh.name = am.mName.length ? am.mName.C_Str() : "mesh " + std::to_string(index);
  const size_t nv = am.mNumVertices;
  if (nv > 0 && !am.mVertices) return err(c, name, "has no positions");
  mesh.positions.resize(nv);
  for (size_t v = 0; v < nv; ++v) {
    const aiVector3D& p = am.mVertices[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return err(c, name, "position " + std::to_string(v) + " is not finite");
    mesh.positions[v] = {p.x, p.y, p.z};
  }
  for (unsigned f = 0; f < am.mNumFaces; ++f) {
    const aiFace& face = am.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines (SortByPType drops them first)
    for (unsigned k = 0; k < 3; ++k)
      if (face.mIndices[k] >= nv)
        return err(c, name, "face " + std::to_string(f) + ": index " + std::to_string(face.mIndices[k]) +
                                " out of range (" + std::to_string(nv) + " vertices)");
    mesh.indices.insert(mesh.indices.end(), face.mIndices, face.mIndices + 3);
  }
  bool normalsOk = am.mNormals != nullptr;
  for (size_t v = 0; normalsOk && v < nv; ++v) {
    const aiVector3D& n = am.mNormals[v];
    normalsOk = std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z);
  }
  if (normalsOk) {
    mesh.normals.resize(nv);
    for (size_t v = 0; v < nv; ++v) {
      const glm::vec3 n(am.mNormals[v].x, am.mNormals[v].y, am.mNormals[v].z);
      const float len = glm::length(n);
      mesh.normals[v] = len > 1e-20f ? n / len : glm::vec3(0, 1, 0);
    }
  } else {
    mesh.normals = computeAreaWeightedNormals(mesh.positions, mesh.indices);
    ++c.ch.report.normalsComputed;
  }
  if (am.mColors[0]) {
    mesh.colors.resize(nv);
    for (size_t v = 0; v < nv; ++v) {
      const aiColor4D& col = am.mColors[0][v];
      const glm::vec4 rgba(col.r, col.g, col.b, col.a);
      mesh.colors[v] = glm::any(glm::isnan(rgba)) ? glm::vec4(1.0f) : glm::clamp(rgba, 0.0f, 1.0f);
    }
  }
  const int tagSet = c.collada ? colladaTagSet(am) : -1;
  if (am.mTextureCoords[0] && tagSet != 0) {  // assimp's v runs upwards (OpenGL); glTF's and ours run down the image
    mesh.texcoords0.resize(nv);
    for (size_t v = 0; v < nv; ++v) {
      const aiVector3D& t = am.mTextureCoords[0][v];
      mesh.texcoords0[v] = std::isfinite(t.x) && std::isfinite(t.y) ? glm::vec2(t.x, 1.0f - t.y) : glm::vec2(0.0f);
    }
  }
  if (am.mMaterialIndex < c.s.mNumMaterials) mesh.material = int(am.mMaterialIndex);
  if (auto st = readMorphTargets(c, am, name, mesh); !st) return Error{st.error()};
  readColladaMorphTargets(c, am, tagSet, name, mesh);

  if (auto st = readSkin(c, am, name, mesh, skinOut); !st) return Error{st.error()};
  if (mesh.indices.empty()) c.ch.report.warnings.push_back(name + ": no triangles");
  return mesh;
}

Status readMeshes(Ctx& c) {
  std::vector<int> skinOfMesh(c.s.mNumMeshes, -1);
  for (unsigned i = 0; i < c.s.mNumMeshes; ++i) {
    auto m = readMesh(c, i, skinOfMesh[i]);
    if (!m) return Error{m.error()};
    c.ch.meshes.push_back(std::move(*m));
  }
  for (Node& n : c.ch.nodes)
    if (n.mesh >= 0) n.skin = skinOfMesh[n.mesh];
  return {};
}

// ---------------------------------------------------------------------------
// Animations.

template <class Key, class Convert>
Status readKeys(const Ctx& c, const std::string& where, const Key* keys, unsigned count, double tps,
                Channel& out, Convert convert) {
  out.timesSec.resize(count);
  out.values.resize(count);
  for (unsigned k = 0; k < count; ++k) {
    const double t = keys[k].mTime / tps;
    if (!std::isfinite(t)) return err(c, where, "key " + std::to_string(k) + ": time is not finite");
    if (k > 0 && t < out.timesSec[k - 1]) return err(c, where, "key times decrease at key " + std::to_string(k));
    out.timesSec[k] = float(t);
    auto v = convert(keys[k].mValue);
    if (!v) return err(c, where, "key " + std::to_string(k) + ": value is not finite (or a zero quaternion)");
    out.values[k] = *v;
  }
  return {};
}

std::optional<glm::vec4> vecValue(const aiVector3D& v) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return std::nullopt;
  return glm::vec4(v.x, v.y, v.z, 0.0f);
}

std::optional<glm::vec4> quatValue(const aiQuaternion& q) {
  const glm::vec4 v(q.x, q.y, q.z, q.w);
  const float len = glm::length(v);
  if (!std::isfinite(len) || len < 1e-6f) return std::nullopt;
  return v / len;
}

Status readAnimations(Ctx& c) {
  for (unsigned a = 0; a < c.s.mNumAnimations; ++a) {
    const aiAnimation* an = c.s.mAnimations[a];
    if (!an) continue;
    const std::string where = label("animation", a, an->mName);
    AnimationClip clip;
    clip.name = an->mName.length ? an->mName.C_Str() : "animation " + std::to_string(a);
    double tps = an->mTicksPerSecond;
    if (!(tps > 0.0) || !std::isfinite(tps)) {
      tps = 25.0;
      c.ch.report.warnings.push_back(where + ": no ticks per second; 25 assumed");
    }
    for (unsigned k = 0; k < an->mNumChannels; ++k) {
      const aiNodeAnim* na = an->mChannels[k];
      if (!na) continue;
      auto node = c.nodeByName.find(na->mNodeName.C_Str());
      if (node == c.nodeByName.end()) {
        c.ch.report.warnings.push_back(where + ": channel for '" + std::string(na->mNodeName.C_Str()) +
                                       "', which names no node; skipped");
        continue;
      }
      const std::string chWhere = where + " channel '" + node->first + "'";
      const struct { ChannelPath path; unsigned count; } parts[] = {{ChannelPath::Translation, na->mNumPositionKeys},
                                                                    {ChannelPath::Rotation, na->mNumRotationKeys},
                                                                    {ChannelPath::Scale, na->mNumScalingKeys}};
      for (const auto& part : parts) {
        if (part.count == 0) continue;
        Channel out;
        out.node = node->second;
        out.path = part.path;
        out.interpolation = Interpolation::Linear;
        Status st = part.path == ChannelPath::Translation
                        ? readKeys(c, chWhere + " translation", na->mPositionKeys, part.count, tps, out, vecValue)
                    : part.path == ChannelPath::Rotation
                        ? readKeys(c, chWhere + " rotation", na->mRotationKeys, part.count, tps, out, quatValue)
                        : readKeys(c, chWhere + " scale", na->mScalingKeys, part.count, tps, out, vecValue);
        if (!st) return st;
        clip.durationSec = std::max(clip.durationSec, out.timesSec.back());
        clip.channels.push_back(std::move(out));
      }
    }
    for (unsigned k = 0; k < an->mNumMorphMeshChannels; ++k)
      if (const aiMeshMorphAnim* mm = an->mMorphMeshChannels[k])
        if (auto st = readMorphChannel(c, where, *mm, tps, clip); !st) return st;
    if (an->mNumMeshChannels > 0) c.ch.report.unsupported.push_back("vertex animation (" + where + ")");
    c.ch.clips.push_back(std::move(clip));
  }
  return {};
}

// ---------------------------------------------------------------------------
// Materials: base colour and its texture. A texture outside the file's folder is dropped.

std::string textureUri(Ctx& c, const std::string& where, const std::string& raw, bool& embedded) {
  embedded = !raw.empty() && (raw[0] == '*' || c.s.GetEmbeddedTexture(raw.c_str()) != nullptr);
  if (raw.empty() || embedded) return {};
  std::string uri = raw;
  std::replace(uri.begin(), uri.end(), '\\', '/');
  const bool absolute = uri[0] == '/' || (uri.size() > 1 && uri[1] == ':');
  std::error_code ec;
  const fs::path full = fs::weakly_canonical(c.folder / uri, ec);
  std::string why;
  if (absolute) why = "absolute paths are not allowed";
  else if (ec || !isInside(full, c.folder)) why = "resolves outside the file's folder";
  if (!why.empty()) {
    c.ch.report.warnings.push_back(where + ": texture '" + raw + "': " + why + "; not used");
    return {};
  }
  if (!fs::is_regular_file(full, ec)) c.ch.report.warnings.push_back(where + ": texture '" + raw + "': file not found");
  return fs::path(uri).lexically_normal().generic_string();
}

// Decodes a material's base colour texture (a file in the folder, or embedded in the
// file: compressed bytes, or raw BGRA texels) into c.ch.textures; returns its index, or -1
// with a warning naming the texture and the reason (the factor colour is drawn).
int readTexture(Ctx& c, const std::string& where, const std::string& raw, const std::string& uri, bool embedded) {
  Result<TextureImage> t = Error{"no texture"};
  if (embedded) {
    const aiTexture* at = c.s.GetEmbeddedTexture(raw.c_str());
    const std::string name = "embedded texture '" + raw + "'";
    if (!at || !at->pcData) t = Error{name + ": no data"};
    else if (at->mHeight == 0)
      t = decodeTextureImage(reinterpret_cast<const unsigned char*>(at->pcData), at->mWidth, name);
    else if (at->mWidth > unsigned(kMaxTextureSide) || at->mHeight > unsigned(kMaxTextureSide))
      t = Error{name + ": " + std::to_string(at->mWidth) + " x " + std::to_string(at->mHeight) +
                " pixels is over the texture budget"};
    else {
      auto px = std::make_shared<std::vector<uint8_t>>(size_t(at->mWidth) * at->mHeight * 4);
      for (size_t i = 0; i < size_t(at->mWidth) * at->mHeight; ++i) {
        const aiTexel& x = at->pcData[i];
        (*px)[4 * i] = x.r, (*px)[4 * i + 1] = x.g, (*px)[4 * i + 2] = x.b, (*px)[4 * i + 3] = x.a;
      }
      TextureImage img;
      img.name = name;
      img.width = int(at->mWidth);
      img.height = int(at->mHeight);
      img.rgba = std::move(px);
      t = std::move(img);
    }
  } else if (!uri.empty()) {
    t = loadTextureFile(c.folder.string(), uri);
  }
  if (!t) {
    c.ch.report.warnings.push_back(c.file + ": " + where + ": " + t.error() + "; drawn in its factor colour");
    return -1;
  }
  c.ch.textures.push_back(std::move(*t));
  return int(c.ch.textures.size()) - 1;
}

void readMaterials(Ctx& c) {
  for (unsigned i = 0; i < c.s.mNumMaterials; ++i) {
    const aiMaterial* am = c.s.mMaterials[i];
    Material m;
    if (!am) {
      c.ch.materials.push_back(m);
      continue;
    }
    aiString name;
    if (am->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
    if (m.name.empty()) m.name = "material " + std::to_string(i);
    aiColor4D col(1.0f, 1.0f, 1.0f, 1.0f);
    if (am->Get(AI_MATKEY_BASE_COLOR, col) != AI_SUCCESS && am->Get(AI_MATKEY_COLOR_DIFFUSE, col) == AI_SUCCESS) {
      float opacity = 1.0f;
      if (am->Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && std::isfinite(opacity)) col.a = opacity;
    }
    const glm::vec4 rgba(col.r, col.g, col.b, col.a);
    if (!glm::any(glm::isnan(rgba)) && !glm::any(glm::isinf(rgba))) m.baseColorFactor = glm::clamp(rgba, 0.0f, 1.0f);
    aiString tex;
    if (am->GetTexture(aiTextureType_BASE_COLOR, 0, &tex) == AI_SUCCESS ||
        am->GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS)
    {
      m.baseColorTextureUri = textureUri(c, label("material", i, name), tex.C_Str(), m.baseColorTextureEmbedded);
      std::error_code ec;  // a missing file is warned about once, by textureUri
      if (m.baseColorTextureEmbedded ||
          (!m.baseColorTextureUri.empty() && fs::is_regular_file(c.folder / m.baseColorTextureUri, ec)))
        m.baseColorTexture = readTexture(c, label("material", i, name), tex.C_Str(), m.baseColorTextureUri,
                                         m.baseColorTextureEmbedded);
    }
    c.ch.materials.push_back(std::move(m));
  }
}

// ---------------------------------------------------------------------------
// Units and axes.

std::string unitName(double metresPerUnit) {
  static const struct { double m; const char* name; } known[] = {
      {1.0, "metres"},   {0.01, "centimetres"}, {0.001, "millimetres"}, {0.1, "decimetres"},
      {1000.0, "kilometres"}, {0.0254, "inches"}, {0.3048, "feet"},      {0.9144, "yards"}};
  for (const auto& k : known)
    if (std::abs(metresPerUnit - k.m) <= 1e-6 * k.m) return k.name;
  char buf[64];
  std::snprintf(buf, sizeof buf, "units of %g m", metresPerUnit);
  return buf;
}

const aiMetadataEntry* metadata(const aiScene& s, const char* key) {
  if (!s.mMetaData) return nullptr;
  for (unsigned i = 0; i < s.mMetaData->mNumProperties; ++i)
    if (s.mMetaData->mKeys[i] == aiString(key) && s.mMetaData->mValues[i].mData) return &s.mMetaData->mValues[i];
  return nullptr;
}

std::optional<double> metadataNumber(const aiScene& s, const char* key) {
  const aiMetadataEntry* e = metadata(s, key);
  if (!e) return std::nullopt;
  switch (e->mType) {
    case AI_INT32: return double(*static_cast<const int32_t*>(e->mData));
    case AI_UINT64: return double(*static_cast<const uint64_t*>(e->mData));
    case AI_FLOAT: return double(*static_cast<const float*>(e->mData));
    case AI_DOUBLE: return *static_cast<const double*>(e->mData);
    default: return std::nullopt;
  }
}

// Collada's <unit meter="0.01" name="centimeter"/> inside <asset>; assimp scales the root by
// it, so the importer undoes that to keep the file's units. nullopt when there is none.
std::optional<double> colladaUnit(const std::string& bytes) {
  const size_t asset = bytes.find("<asset");
  const size_t assetEnd = bytes.find("</asset>", asset == std::string::npos ? 0 : asset);
  if (asset == std::string::npos || assetEnd == std::string::npos) return std::nullopt;
  const size_t unit = bytes.find("<unit", asset);
  if (unit == std::string::npos || unit > assetEnd) return std::nullopt;
  const size_t close = bytes.find('>', unit);
  const size_t meter = bytes.find("meter=", unit);
  if (meter == std::string::npos || close == std::string::npos || meter > close) return std::nullopt;
  const double m = std::strtod(bytes.c_str() + meter + 7, nullptr);
  if (!std::isfinite(m) || m <= 0.0) return std::nullopt;
  return m;
}

// FBX's axis settings as a rotation into +Y up, +Z front, +X across (the glTF frame);
// nullopt when the settings are missing, already that frame, or not a rotation.
std::optional<glm::mat4> fbxAxisRotation(const Ctx& c) {
  const char* keys[6] = {"CoordAxis", "CoordAxisSign", "UpAxis", "UpAxisSign", "FrontAxis", "FrontAxisSign"};
  double v[6];
  for (int i = 0; i < 6; ++i) {
    auto n = metadataNumber(c.s, keys[i]);
    if (!n) return std::nullopt;
    v[i] = *n;
  }
  glm::mat3 rows(0.0f);  // rows[r] = file axis that becomes world axis r
  for (int r = 0; r < 3; ++r) {
    const int axis = int(v[2 * r]);
    if (axis < 0 || axis > 2) return std::nullopt;
    rows[r][axis] = v[2 * r + 1] < 0 ? -1.0f : 1.0f;
  }
  const glm::mat3 toWorld = glm::transpose(rows);  // columns: world axes in file coordinates
  const glm::mat3 m = glm::transpose(toWorld);       // file -> world
  if (std::abs(glm::determinant(m) - 1.0f) > 1e-4f) {
    c.ch.report.warnings.push_back("FBX axis settings mirror the scene; used as they are");
    return std::nullopt;
  }
  if (m == glm::mat3(1.0f)) return std::nullopt;
  return glm::mat4(m);
}

void readUnitAndAxes(Ctx& c, const std::string& format, const std::string& bytes) {
  Character& ch = c.ch;
  if (format == "FBX") {
    if (auto f = metadataNumber(c.s, "UnitScaleFactor"); f && *f > 0.0 && std::isfinite(*f)) {
      ch.unit.metresPerUnit = *f * 0.01;  // FBX: centimetres per unit
      ch.unit.declared = true;
    } else {
      ch.unit.metresPerUnit = 0.01;  // FBX's default unit
      ch.unit.declared = false;
    }
    if (auto r = fbxAxisRotation(c)) ch.nodes[0].rest = safeDecompose(*r * ch.nodes[0].rest.matrix());
  } else if (format == "Collada") {
    auto m = colladaUnit(bytes);
    ch.unit.metresPerUnit = m.value_or(1.0);
    ch.unit.declared = m.has_value();
    if (m && *m != 1.0)  // assimp scaled the root by the unit (uniform, so it commutes with the up-axis turn)
      ch.nodes[0].rest = safeDecompose(ch.nodes[0].rest.matrix() * glm::scale(glm::mat4(1.0f), glm::vec3(float(1.0 / *m))));
  } else {
    ch.unit.metresPerUnit = 1.0;
    ch.unit.declared = false;
  }
  ch.unit.name = unitName(ch.unit.metresPerUnit);
  if (!ch.unit.declared) ch.unit.name += " (assumed: the file declares no unit)";
}

// Blender's Collada skins: Blender writes an identity <bind_shape_matrix> and reads its own skinned
// meshes as placed by their node (a mesh under a scaled armature takes the armature's scale), where
// the Collada rule (joint x inverse bind x bind shape) ignores the node. For a file Blender wrote,
// each skinned mesh node's transform below the scene root is folded into its skin's inverse bind
// matrices, so the character stands where Blender shows it (identity nodes change nothing).
size_t placeBlenderColladaSkins(Character& ch) {
  size_t changed = 0;
  for (size_t n = 0; n < ch.nodes.size(); ++n) {
    const Node& node = ch.nodes[n];
    if (node.mesh < 0 || node.skin < 0 || size_t(node.skin) >= ch.skins.size()) continue;
    glm::mat4 m(1.0f);
    for (int i = int(n); i > 0; i = ch.nodes[size_t(i)].parent) m = ch.nodes[size_t(i)].rest.matrix() * m;
    float off = 0.0f;
    for (int k = 0; k < 16; ++k) off = std::max(off, std::abs(m[k / 4][k % 4] - (k / 4 == k % 4 ? 1.0f : 0.0f)));
    if (off < 1e-6f) continue;
    for (glm::mat4& ibm : ch.skins[size_t(node.skin)].inverseBindMatrices) ibm = ibm * m;
    ++changed;
  }
  return changed;
}

// ---------------------------------------------------------------------------
// FBX pivot helper nodes ("NAME_$AssimpFbx$_PreRotation" ...): a run of them that no channel
// animates is folded into the node below it, when their product is still T * R * S.

bool isFbxHelper(const std::string& name) { return name.find("_$AssimpFbx$_") != std::string::npos; }

void compactNodes(Character& ch, const std::vector<char>& removed) {
  std::vector<int> remap(ch.nodes.size(), -1);
  std::vector<Node> kept;
  for (size_t i = 0; i < ch.nodes.size(); ++i)
    if (!removed[i]) {
      remap[i] = int(kept.size());
      kept.push_back(std::move(ch.nodes[i]));
    }
  auto map = [&](int& i) { if (i >= 0) i = remap[i]; };
  for (Node& n : kept) {
    map(n.parent);
    for (int& k : n.children) map(k);
  }
  for (int& r : ch.roots) map(r);
  for (Skin& s : ch.skins) {
    for (int& j : s.joints) map(j);
    map(s.skeletonRoot);
  }
  for (AnimationClip& clip : ch.clips)
    for (Channel& chn : clip.channels) map(chn.node);
  ch.nodes = std::move(kept);
}

size_t foldStaticFbxHelpers(Character& ch) {
  std::vector<char> animated(ch.nodes.size(), 0), removed(ch.nodes.size(), 0);
  for (const AnimationClip& clip : ch.clips)
    for (const Channel& chn : clip.channels) animated[chn.node] = 1;
  size_t folded = 0;
  for (size_t i = 0; i < ch.nodes.size(); ++i) {
    Node& h = ch.nodes[i];
    if (removed[i] || animated[i] || !isFbxHelper(h.name) || h.children.size() != 1 || h.mesh >= 0) continue;
    const int below = h.children[0];
    Node& n = ch.nodes[below];
    if (animated[below]) continue;
    const glm::mat4 product = h.rest.matrix() * n.rest.matrix();
    const Transform t = safeDecompose(product);
    if (decompositionError(product, t) > 1e-5f) continue;
    n.rest = t;
    n.parent = h.parent;
    if (h.parent >= 0) std::replace(ch.nodes[h.parent].children.begin(), ch.nodes[h.parent].children.end(), int(i), below);
    std::replace(ch.roots.begin(), ch.roots.end(), int(i), below);
    removed[i] = 1;
    ++folded;
  }
  if (folded) compactNodes(ch, removed);
  return folded;
}

// ---------------------------------------------------------------------------

std::string formatOf(const std::string& path) {
  const std::string e = lowerExtension(path);
  if (e == ".fbx") return "FBX";
  if (e == ".dae") return "Collada";
  if (e == ".obj") return "OBJ";
  return e.empty() ? "unknown" : e.substr(1);
}

// The first line of assimp's error, without its own prefix.
std::string assimpReason(const char* raw) {
  std::string s = raw ? raw : "";
  if (const size_t nl = s.find('\n'); nl != std::string::npos) s.resize(nl);
  if (s.empty()) s = "not a readable file of this format";
  return s;
}

Status checkDeclaredSizes(const std::string& file, const std::string& format, const std::string& bytes) {
  if (format == "FBX") {
    if (isFbxBinary(bytes)) return checkFbxBinaryDeclaredSizes(file, bytes);
    return checkTextDeclaredCounts(file, bytes, false);
  }
  if (format == "Collada") {
    if (Status counts = checkTextDeclaredCounts(file, bytes, true); !counts) return counts;
    if (Status lists = checkColladaIndexLists(file, bytes); !lists) return lists;
    if (Status weights = checkColladaVertexWeights(file, bytes); !weights) return weights;
    return checkColladaAccessors(file, bytes);
  }
  return {};
}

Result<Character> importImpl(const std::string& path, const AssimpImportLimits& limits) {
  auto bytes = readFile(path, limits.maxFileBytes);  // a regular file under the cap, or an error naming it
  if (!bytes) return Error{bytes.error()};
  const std::string format = formatOf(path);
  if (auto st = checkDeclaredSizes(path, format, *bytes); !st) return Error{st.error()};
  // Read beside assimp, before it: Collada's <morph> controllers (and the document rewritten so
  // that assimp reads the file), FBX's blend shape channel values.
  std::optional<ColladaMorphDocument> collada;
  if (format == "Collada") {
    auto prepared = prepareColladaMorphs(path, *bytes, limits.maxBlendShapeVertices);
    if (!prepared) return Error{prepared.error()};
    collada = std::move(*prepared);
  }
  std::optional<FbxShapeValues> fbxShapeValues;
  std::string fbxShapeProblem;
  if (format == "FBX") {
    auto values = readFbxShapeValues(path, *bytes);
    if (values) fbxShapeValues = std::move(*values);
    else fbxShapeProblem = values.error();
  }
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(fs::absolute(fs::path(path), ec).parent_path(), ec);
  if (ec) return Error{path + ": cannot resolve its folder: " + ec.message()};

  Assimp::Importer importer;
  auto* io = new FolderIOSystem(folder, limits.maxFileBytes);
  importer.SetIOHandler(io);  // the importer owns it
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_CAMERAS, false);
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_LIGHTS, false);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_JoinIdenticalVertices |
                         aiProcess_ValidateDataStructure;
  const aiScene* scene = collada && !collada->document.empty()
                            ? importer.ReadFileFromMemory(collada->document.data(), collada->document.size(), flags, "dae")
                            : importer.ReadFile(path, flags);
  std::vector<std::string> refused = io->refused;
  if (!scene || !scene->mRootNode) {
    if (!refused.empty()) return Error{path + ": " + refused.front()};
    return Error{path + ": cannot be read as " + format + ": " + assimpReason(importer.GetErrorString())};
  }
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)
    return Error{path + ": " + format + " file is incomplete (assimp read no complete scene)"};

  Character ch;
  ch.sourcePath = path;
  ch.format = format;
  Ctx c{path, *scene, limits, folder, ch, {}, collada ? &*collada : nullptr, fbxShapeValues ? &*fbxShapeValues : nullptr,
        {}};
  if (!fbxShapeProblem.empty())
    ch.report.warnings.push_back("blend shape values not read (" + fbxShapeProblem + "); shapes start at weight 0");
  if (fbxShapeValues)
    for (const std::string& n : fbxShapeValues->conflicting)
      ch.report.warnings.push_back("blend shape channels named '" + n + "' have different values; the first is used");
  if (auto st = checkCounts(c); !st) return Error{st.error()};
  if (auto st = readNodes(c); !st) return Error{st.error()};
  if (auto st = readMeshes(c); !st) return Error{st.error()};
  if (auto st = readAnimations(c); !st) return Error{st.error()};
  addColladaWeightChannels(c);
  readMaterials(c);
  readUnitAndAxes(c, format, *bytes);
  if (format == "FBX") foldStaticFbxHelpers(ch);
  if (format == "Collada" && bytes->find("<authoring_tool>Blender") != std::string::npos && placeBlenderColladaSkins(ch))
    ch.report.warnings.push_back("Blender's Collada: skinned meshes placed by their nodes, as Blender reads them");
  for (auto& r : refused) ch.report.warnings.push_back(r);
  if (scene->mNumCameras) ch.report.unsupported.push_back("cameras (" + std::to_string(scene->mNumCameras) + ")");
  if (scene->mNumLights) ch.report.unsupported.push_back("lights (" + std::to_string(scene->mNumLights) + ")");
  if (ch.meshes.empty()) ch.report.warnings.push_back("no meshes");
  std::set<std::string> seen;
  std::vector<std::string> unique;
  for (auto& w : ch.report.warnings)
    if (seen.insert(w).second) unique.push_back(std::move(w));
  ch.report.warnings.swap(unique);
  return ch;
}

}  // namespace

Result<Character> importAssimp(const std::string& path, const AssimpImportLimits& limits) {
  const auto start = std::chrono::steady_clock::now();
  try {
    auto r = importImpl(path, limits);
    if (r) r->report.importMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return r;
  } catch (const std::bad_alloc&) {
    return Error{path + ": cannot be read: out of memory"};
  } catch (const std::exception& e) {
    return Error{path + ": cannot be read: " + e.what()};
  } catch (...) {
    return Error{path + ": cannot be read: unknown failure"};
  }
}

}  // namespace animorph
