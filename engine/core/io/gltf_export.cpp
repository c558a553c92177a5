#include "core/io/gltf_export.h"

#include <unordered_map>

#include "core/util/atomic_file.h"
#include "core/io/glb_writer.h"
#include "core/io/texture_decode.h"
#include "core/rig/morph_targets.h"

namespace animorph {
namespace {

using json = nlohmann::json;
using namespace gltf;

const char* interpolationName(Interpolation i) {
  switch (i) {
    case Interpolation::Step: return "STEP";
    case Interpolation::Linear: return "LINEAR";
    case Interpolation::CubicSpline: return "CUBICSPLINE";
  }
  return "LINEAR";
}

const char* pathName(ChannelPath p) {
  switch (p) {
    case ChannelPath::Translation: return "translation";
    case ChannelPath::Rotation: return "rotation";
    case ChannelPath::Scale: return "scale";
    case ChannelPath::Weights: return "weights";
  }
  return "translation";
}

// The sampler of a Weights channel: one weight per morph target of the node's mesh per key.
Result<json> weightSampler(const Character& c, const Channel& ch, const std::string& label, GlbWriter& w) {
  const int mesh = c.nodes[size_t(ch.node)].mesh;
  const size_t targets = mesh >= 0 && mesh < int(c.meshes.size()) ? c.meshes[size_t(mesh)].morphTargets.size() : 0;
  if (targets == 0) return Error{label + ": animates weights of a node without a mesh with morph targets"};
  if (size_t(ch.weightCount) != targets)
    return Error{label + ": " + std::to_string(ch.weightCount) + " weights per key for " + std::to_string(targets) +
                 " morph targets"};
  const size_t perKey = (ch.interpolation == Interpolation::CubicSpline ? 3 : 1) * targets;
  if (ch.weightValues.size() != perKey * ch.timesSec.size())
    return Error{label + ": " + std::to_string(ch.weightValues.size()) + " weights for " +
                 std::to_string(ch.timesSec.size()) + " keys"};
  int in = w.floats(ch.timesSec.data(), ch.timesSec.size(), 1, "SCALAR", 0, true);
  int out = w.floats(ch.weightValues.data(), ch.weightValues.size(), 1, "SCALAR", 0, false);
  return json{{"input", in}, {"output", out}, {"interpolation", interpolationName(ch.interpolation)}};
}

// The nodes (checked against the meshes and skins); skinOfMesh[m]: the skin of a node drawing mesh m.
Result<json> nodesJson(const Character& c, std::vector<int>& skinOfMesh) {
  const int nodeCount = static_cast<int>(c.nodes.size());
  json nodes = json::array();
  for (int i = 0; i < nodeCount; ++i) {
    const Node& n = c.nodes[i];
    json jn = {{"name", n.name}};
    if (!n.children.empty()) jn["children"] = n.children;
    for (int ch : n.children)
      if (ch < 0 || ch >= nodeCount) return Error{"node " + std::to_string(i) + ": child " + std::to_string(ch) + " does not exist"};
    const Transform& t = n.rest;
    if (t.translation != glm::vec3(0.0f)) jn["translation"] = {t.translation.x, t.translation.y, t.translation.z};
    if (t.rotation != glm::quat(1, 0, 0, 0)) jn["rotation"] = {t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w};
    if (t.scale != glm::vec3(1.0f)) jn["scale"] = {t.scale.x, t.scale.y, t.scale.z};
    if (n.mesh >= 0) {
      if (n.mesh >= static_cast<int>(c.meshes.size())) return Error{"node " + std::to_string(i) + ": mesh does not exist"};
      jn["mesh"] = n.mesh;
    }
    if (n.skin >= 0) {
      if (n.skin >= static_cast<int>(c.skins.size())) return Error{"node " + std::to_string(i) + ": skin does not exist"};
      jn["skin"] = n.skin;
      if (n.mesh >= 0) skinOfMesh[n.mesh] = n.skin;
    }
    nodes.push_back(jn);
  }
  return nodes;
}

// JOINTS_n / WEIGHTS_n of a mesh drawn by a node with skin (checked against its joints).
Status addSkinAttributes(const Character& c, const Mesh& m, int skin, const std::string& label, GlbWriter& w,
                         json& attrs) {
  const size_t nv = m.vertexCount();
  const size_t jointCount = c.skins[skin].joints.size();
  if (m.joints0.size() != nv || m.weights0.size() != nv) return Error{label + ": joints0/weights0 do not match the vertex count"};
  const bool second = !m.joints1.empty();
  if (second && (m.joints1.size() != nv || m.weights1.size() != nv))
    return Error{label + ": joints1/weights1 do not match the vertex count"};
  for (size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 4; ++k)
      if ((m.weights0[v][k] > 0.0f && m.joints0[v][k] >= jointCount) ||
          (second && m.weights1[v][k] > 0.0f && m.joints1[v][k] >= jointCount))
        return Error{label + ": vertex " + std::to_string(v) + " uses a joint outside skin " + std::to_string(skin)};
  // Slots with zero weight point at joint 0 (validators flag anything else).
  auto clean = [](std::vector<glm::uvec4> j, const std::vector<glm::vec4>& wts) {
    for (size_t v = 0; v < j.size(); ++v)
      for (int k = 0; k < 4; ++k)
        if (!(wts[v][k] > 0.0f)) j[v][k] = 0;
    return j;
  };
  attrs["JOINTS_0"] = w.joints(clean(m.joints0, m.weights0));
  attrs["WEIGHTS_0"] = w.floats(&m.weights0.data()->x, nv, 4, "VEC4", kArrayBuffer, false);
  if (second) {
    attrs["JOINTS_1"] = w.joints(clean(m.joints1, m.weights1));
    attrs["WEIGHTS_1"] = w.floats(&m.weights1.data()->x, nv, 4, "VEC4", kArrayBuffer, false);
  }
  return Status::success();
}

// A mesh's morph targets on its primitive, their default weights and names on the mesh.
Status addMorphTargets(const Mesh& m, const std::string& label, GlbWriter& w, json& prim, json& jm) {
  if (std::string bad = checkMorphTargets(m); !bad.empty()) return Error{label + ": " + bad};
  const size_t nv = m.vertexCount();
  json targets = json::array(), names = json::array();
  for (const MorphTarget& mt : m.morphTargets) {
    json t;
    t["POSITION"] = w.floats(&mt.positionDeltas.data()->x, nv, 3, "VEC3", kArrayBuffer, true);
    if (!mt.normalDeltas.empty()) t["NORMAL"] = w.floats(&mt.normalDeltas.data()->x, nv, 3, "VEC3", kArrayBuffer, false);
    targets.push_back(t);
    names.push_back(mt.name);
  }
  prim["targets"] = targets;
  std::vector<float> weights(m.morphTargets.size(), 0.0f);
  for (size_t t = 0; t < weights.size() && t < m.defaultMorphWeights.size(); ++t) weights[t] = m.defaultMorphWeights[t];
  jm["weights"] = weights;
  jm["extras"] = {{"targetNames", names}};  // the names Blender and three.js read
  return Status::success();
}

// Whether m has two or more material parts, each a whole number of triangles inside its index
// list (then each is written as a primitive of its own).
bool hasValidParts(const Mesh& m) {
  if (m.parts.size() < 2) return false;
  for (const Mesh::Part& p : m.parts)
    if (p.indexCount == 0 || p.indexCount % 3 != 0 || size_t(p.firstIndex) + p.indexCount > m.indices.size())
      return false;
  return true;
}

// The triangles of part p as a mesh of their own: the vertices they use (in order of first use),
// every per-vertex array and morph target cut to them, the indices renumbered. Vertices shared
// by two parts are written once per part, as a glTF primitive holds its own vertices.
Mesh meshPart(const Mesh& m, const Mesh::Part& p) {
  Mesh out;
  out.name = m.name;
  out.material = p.material;
  out.defaultMorphWeights = m.defaultMorphWeights;
  for (const MorphTarget& t : m.morphTargets) out.morphTargets.push_back({t.name, {}, {}});
  std::unordered_map<uint32_t, uint32_t> remap;
  auto take = [](const auto& from, auto& to, uint32_t v) {
    if (v < from.size()) to.push_back(from[v]);
  };
  for (uint32_t k = 0; k < p.indexCount; ++k) {
    const uint32_t v = m.indices[p.firstIndex + k];
    auto [it, added] = remap.try_emplace(v, uint32_t(out.positions.size()));
    out.indices.push_back(it->second);
    if (!added) continue;
    take(m.positions, out.positions, v);
    take(m.normals, out.normals, v);
    take(m.colors, out.colors, v);
    take(m.texcoords0, out.texcoords0, v);
    take(m.joints0, out.joints0, v);
    take(m.joints1, out.joints1, v);
    take(m.weights0, out.weights0, v);
    take(m.weights1, out.weights1, v);
    for (size_t t = 0; t < m.morphTargets.size(); ++t) {
      take(m.morphTargets[t].positionDeltas, out.morphTargets[t].positionDeltas, v);
      take(m.morphTargets[t].normalDeltas, out.morphTargets[t].normalDeltas, v);
    }
  }
  return out;
}

// Errors glTF cannot hold in m's vertex arrays: no vertices, normals or colours not one per
// vertex, an index out of range. label names the mesh.
Status checkVertexArrays(const Mesh& m, const std::string& label) {
  const size_t nv = m.vertexCount();
  if (nv == 0) return Error{label + ": has no vertices (glTF accessors cannot be empty)"};
  if (m.normals.size() != nv) return Error{label + ": " + std::to_string(m.normals.size()) + " normals for " + std::to_string(nv) + " vertices"};
  if (!m.colors.empty() && m.colors.size() != nv)
    return Error{label + ": " + std::to_string(m.colors.size()) + " colours for " + std::to_string(nv) + " vertices"};
  for (uint32_t i : m.indices)
    if (i >= nv) return Error{label + ": index " + std::to_string(i) + " out of range (" + std::to_string(nv) + " vertices)"};
  return Status::success();
}

// One triangle primitive of mesh m drawn with `material` (skinned when skin >= 0), its arrays
// into w; the morph targets' default weights and names onto jm. label names the mesh in errors.
Result<json> primitiveJson(const Character& c, const Mesh& m, int material, int skin, const std::string& label,
                           GlbWriter& w, json& jm) {
  const size_t nv = m.vertexCount();
  if (Status st = checkVertexArrays(m, label); !st) return Error{st.error()};
  json attrs;
  attrs["POSITION"] = w.floats(&m.positions.data()->x, nv, 3, "VEC3", kArrayBuffer, true);
  attrs["NORMAL"] = w.normals(m.normals);
  if (!m.colors.empty()) attrs["COLOR_0"] = w.floats(&m.colors.data()->x, nv, 4, "VEC4", kArrayBuffer, false);
  if (m.texcoords0.size() == nv) attrs["TEXCOORD_0"] = w.floats(&m.texcoords0.data()->x, nv, 2, "VEC2", kArrayBuffer, false);
  if (skin >= 0 && nv > 0)
    if (Status st = addSkinAttributes(c, m, skin, label, w, attrs); !st) return Error{st.error()};
  json prim = {{"attributes", attrs}, {"mode", 4}};
  if (!m.indices.empty()) prim["indices"] = w.indices(m.indices, nv);
  if (material >= 0 && size_t(material) < c.materials.size()) prim["material"] = material;
  if (!m.morphTargets.empty())
    if (Status st = addMorphTargets(m, label, w, prim, jm); !st) return Error{st.error()};
  return prim;
}

// Mesh mi as its triangle primitives (skinned when skin >= 0), its arrays into w: one per material
// part when it has two or more (Mesh::parts), else one drawn with Mesh::material.
Result<json> meshJson(const Character& c, size_t mi, int skin, GlbWriter& w) {
  const Mesh& m = c.meshes[mi];
  const std::string label = "mesh " + std::to_string(mi) + " '" + m.name + "'";
  json jm = {{"name", m.name}}, prims = json::array();
  if (Status st = checkVertexArrays(m, label); !st) return Error{st.error()};
  if (std::string bad = checkMorphTargets(m); !bad.empty()) return Error{label + ": " + bad};
  if (!hasValidParts(m)) {
    auto prim = primitiveJson(c, m, m.material, skin, label, w, jm);
    if (!prim) return Error{prim.error()};
    prims.push_back(*prim);
  }
  for (size_t k = 0; hasValidParts(m) && k < m.parts.size(); ++k) {
    auto prim = primitiveJson(c, meshPart(m, m.parts[k]), m.parts[k].material, skin, label + " part " + std::to_string(k), w, jm);
    if (!prim) return Error{prim.error()};
    prims.push_back(*prim);
  }
  jm["primitives"] = prims;
  return jm;
}

Result<json> skinsJson(const Character& c, GlbWriter& w) {
  const int nodeCount = static_cast<int>(c.nodes.size());
  json skins = json::array();
  for (size_t si = 0; si < c.skins.size(); ++si) {
    const Skin& s = c.skins[si];
    for (int j : s.joints)
      if (j < 0 || j >= nodeCount) return Error{"skin " + std::to_string(si) + ": joint node " + std::to_string(j) + " does not exist"};
    std::vector<glm::mat4> ibm(s.joints.size(), glm::mat4(1.0f));
    for (size_t j = 0; j < ibm.size() && j < s.inverseBindMatrices.size(); ++j) ibm[j] = s.inverseBindMatrices[j];
    json js = {{"name", s.name}, {"joints", s.joints}};
    js["inverseBindMatrices"] = w.floats(&ibm.data()[0][0][0], ibm.size(), 16, "MAT4", 0, false);
    if (s.skeletonRoot >= 0) js["skeleton"] = s.skeletonRoot;
    skins.push_back(js);
  }
  return skins;
}

// A clip with at least one channel as a glTF animation (its keys checked), its arrays into w.
Result<json> animationJson(const Character& c, const AnimationClip& clip, GlbWriter& w) {
  const int nodeCount = static_cast<int>(c.nodes.size());
  json channels = json::array(), samplers = json::array();
  for (size_t k = 0; k < clip.channels.size(); ++k) {
    const Channel& ch = clip.channels[k];
    const std::string label = "animation '" + clip.name + "' channel " + std::to_string(k);
    if (ch.node < 0 || ch.node >= nodeCount) return Error{label + ": target node does not exist"};
    if (ch.timesSec.empty()) return Error{label + ": no keys"};
    for (size_t i = 1; i < ch.timesSec.size(); ++i)
      if (!(ch.timesSec[i] > ch.timesSec[i - 1])) return Error{label + ": key times must increase (key " + std::to_string(i) + ")"};
    const size_t perKey = ch.interpolation == Interpolation::CubicSpline ? 3 : 1;
    if (ch.path == ChannelPath::Weights) {
      auto sampler = weightSampler(c, ch, label, w);
      if (!sampler) return Error{sampler.error()};
      samplers.push_back(*sampler);
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", ch.node}, {"path", "weights"}}}});
      continue;
    }
    if (ch.values.size() != perKey * ch.timesSec.size())
      return Error{label + ": " + std::to_string(ch.values.size()) + " values for " + std::to_string(ch.timesSec.size()) + " keys"};
    const bool rot = ch.path == ChannelPath::Rotation;
    std::vector<float> vals;
    vals.reserve(ch.values.size() * 4);
    for (const auto& v : ch.values) {
      vals.insert(vals.end(), {v.x, v.y, v.z});
      if (rot) vals.push_back(v.w);
    }
    int in = w.floats(ch.timesSec.data(), ch.timesSec.size(), 1, "SCALAR", 0, true);
    int out = w.floats(vals.data(), ch.values.size(), rot ? 4 : 3, rot ? "VEC4" : "VEC3", 0, false);
    samplers.push_back({{"input", in}, {"output", out}, {"interpolation", interpolationName(ch.interpolation)}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", ch.node}, {"path", pathName(ch.path)}}}});
  }
  return json{{"name", clip.name}, {"channels", channels}, {"samplers", samplers}};
}

int glWrap(TextureWrap w) {
  return w == TextureWrap::ClampToEdge ? 33071 : w == TextureWrap::MirroredRepeat ? 33648 : 10497;
}
int glFilter(TextureFilter f) { return f == TextureFilter::Nearest ? 9728 : 9729; }

// Materials (name, base colour factor and texture) and their textures as embedded PNG images.
void writeMaterials(const Character& c, GlbWriter& w, json& root) {
  json materials = json::array(), images = json::array(), textures = json::array(), samplers = json::array();
  std::vector<int> textureIndex(c.textures.size(), -1);
  for (size_t t = 0; t < c.textures.size(); ++t) {
    const std::vector<uint8_t> png = encodeTexturePng(c.textures[t]);
    if (png.empty()) continue;
    const TextureImage& ti = c.textures[t];
    images.push_back({{"bufferView", w.view(png.data(), png.size(), 0)}, {"mimeType", "image/png"}});
    samplers.push_back({{"wrapS", glWrap(ti.wrapS)}, {"wrapT", glWrap(ti.wrapT)}, {"magFilter", glFilter(ti.magFilter)},
                        {"minFilter", glFilter(ti.minFilter)}});
    textureIndex[t] = int(textures.size());
    textures.push_back({{"source", images.size() - 1}, {"sampler", samplers.size() - 1}});
  }
  for (const Material& mat : c.materials) {
    const glm::vec4& f = mat.baseColorFactor;
    json pbr = {{"baseColorFactor", {f.r, f.g, f.b, f.a}}};
    if (mat.baseColorTexture >= 0 && size_t(mat.baseColorTexture) < textureIndex.size() &&
        textureIndex[size_t(mat.baseColorTexture)] >= 0)
      pbr["baseColorTexture"] = {{"index", textureIndex[size_t(mat.baseColorTexture)]}};
    materials.push_back({{"name", mat.name}, {"pbrMetallicRoughness", pbr}});
  }
  if (!materials.empty()) root["materials"] = materials;
  if (!images.empty()) root["images"] = images, root["textures"] = textures, root["samplers"] = samplers;
}

}  // namespace

Result<std::string> exportGlbBytes(const Character& c) {
  GlbWriter w;
  json root;
  root["asset"] = {{"version", "2.0"}, {"generator", "Animorph"}};
  // Meshes drawn by a skinned node carry joints and weights.
  std::vector<int> skinOfMesh(c.meshes.size(), -1);
  auto nodes = nodesJson(c, skinOfMesh);
  if (!nodes) return Error{nodes.error()};
  root["nodes"] = *nodes;
  root["scene"] = 0;
  root["scenes"] = json::array({{{"nodes", c.roots}}});
  json meshes = json::array();
  for (size_t mi = 0; mi < c.meshes.size(); ++mi) {
    auto jm = meshJson(c, mi, skinOfMesh[mi], w);
    if (!jm) return Error{jm.error()};
    meshes.push_back(*jm);
  }
  if (!meshes.empty()) root["meshes"] = meshes;
  writeMaterials(c, w, root);
  auto skins = skinsJson(c, w);
  if (!skins) return Error{skins.error()};
  if (!skins->empty()) root["skins"] = *skins;
  json anims = json::array();
  for (const AnimationClip& clip : c.clips) {
    if (clip.channels.empty()) continue;  // glTF requires at least one channel
    auto anim = animationJson(c, clip, w);
    if (!anim) return Error{anim.error()};
    anims.push_back(*anim);
  }
  if (!anims.empty()) root["animations"] = anims;
  return w.finish(std::move(root));
}

Status exportGlb(const Character& c, const std::string& path) {
  auto bytes = exportGlbBytes(c);
  if (!bytes) return Error{path + ": " + bytes.error()};
  return writeFileAtomic(path, *bytes);
}

}  // namespace animorph
