#include "test_character.h"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

namespace animorph::test {
namespace {

std::string base64(const std::vector<unsigned char>& data) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < data.size(); i += 3) {
    unsigned v = data[i] << 16 | data[i + 1] << 8 | data[i + 2];
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
  }
  if (i + 1 == data.size()) {
    unsigned v = data[i] << 16;
    out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == data.size()) {
    unsigned v = data[i] << 16 | data[i + 1] << 8;
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
  }
  return out;
}

class BufferWriter {
 public:
  // Appends raw bytes (4-byte aligned) and returns the buffer view index.
  int add(const void* data, size_t size, nlohmann::json& views, int target = 0) {
    while (bytes_.size() % 4) bytes_.push_back(0);
    size_t offset = bytes_.size();
    const auto* p = static_cast<const unsigned char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
    if (target) v["target"] = target;
    views.push_back(v);
    return static_cast<int>(views.size()) - 1;
  }
  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
};

}  // namespace

Character writeTestCharacter(const std::string& path) {
  Character c;
  c.sourcePath = path;
  Mesh m;
  m.name = "BodyMesh";
  m.positions = {{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.5f, 2.0f, 0.0f}, {-0.5f, 2.0f, 0.0f}};
  m.normals = std::vector<glm::vec3>(4, glm::vec3(0.0f, 0.0f, 1.0f));
  m.indices = {0, 1, 2, 0, 2, 3};
  m.joints0 = {{0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  m.weights0 = std::vector<glm::vec4>(4, glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  m.joints1 = std::vector<glm::uvec4>(4, glm::uvec4(0));
  m.weights1 = std::vector<glm::vec4>(4, glm::vec4(0.0f));
  c.meshes.push_back(m);

  c.nodes.resize(4);
  c.nodes[0].name = "Body";
  c.nodes[0].mesh = 0;
  c.nodes[0].skin = 0;
  c.nodes[1].name = "Armature";
  c.nodes[1].children = {2};
  c.nodes[2].name = "hip";
  c.nodes[2].parent = 1;
  c.nodes[2].children = {3};
  c.nodes[3].name = "spine";
  c.nodes[3].parent = 2;
  c.nodes[3].rest.translation = {0.0f, 1.0f, 0.0f};
  c.roots = {0, 1};

  Skin skin;
  skin.name = "Skin";
  skin.joints = {2, 3};
  skin.inverseBindMatrices = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -1.0f, 0.0f))};
  skin.skeletonRoot = 2;
  c.skins.push_back(skin);

  AnimationClip clip;
  clip.name = "wave";
  clip.durationSec = 1.0f;
  Channel rot;
  rot.node = 3;
  rot.path = ChannelPath::Rotation;
  rot.timesSec = {0.0f, 0.25f, 0.5f, 1.0f};
  float s = std::sin(0.25f), co = std::cos(0.25f);
  rot.values = {{0, 0, 0, 1}, {0, 0, s, co}, {0, 0, 0, 1}, {0, 0, 0, 1}};  // x, y, z, w
  Channel tr;
  tr.node = 2;
  tr.path = ChannelPath::Translation;
  tr.timesSec = {0.0f, 1.0f};
  tr.values = {{0, 0, 0, 0}, {0, 0.2f, 0, 0}};
  clip.channels = {rot, tr};
  c.clips.push_back(clip);

  // The same thing as glTF.
  using json = nlohmann::json;
  json views = json::array(), accessors = json::array();
  BufferWriter buf;
  auto accessor = [&](int view, int componentType, size_t count, const char* type, json extra = json::object()) {
    json a = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
    for (auto& [k, v] : extra.items()) a[k] = v;
    accessors.push_back(a);
    return static_cast<int>(accessors.size()) - 1;
  };
  int aPos = accessor(buf.add(m.positions.data(), 4 * 12, views, 34962), 5126, 4, "VEC3",
                      {{"min", {-0.5, 0.0, 0.0}}, {"max", {0.5, 2.0, 0.0}}});
  int aNrm = accessor(buf.add(m.normals.data(), 4 * 12, views, 34962), 5126, 4, "VEC3");
  unsigned char joints[16] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  int aJnt = accessor(buf.add(joints, 16, views, 34962), 5121, 4, "VEC4");
  int aWgt = accessor(buf.add(m.weights0.data(), 4 * 16, views, 34962), 5126, 4, "VEC4");
  uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  int aIdx = accessor(buf.add(idx, sizeof idx, views, 34963), 5123, 6, "SCALAR");
  glm::mat4 ibm[2] = {skin.inverseBindMatrices[0], skin.inverseBindMatrices[1]};
  int aIbm = accessor(buf.add(ibm, sizeof ibm, views), 5126, 2, "MAT4");
  int aRotT = accessor(buf.add(rot.timesSec.data(), 16, views), 5126, 4, "SCALAR", {{"min", {0.0}}, {"max", {1.0}}});
  int aRotV = accessor(buf.add(rot.values.data(), 64, views), 5126, 4, "VEC4");
  int aTrT = accessor(buf.add(tr.timesSec.data(), 8, views), 5126, 2, "SCALAR", {{"min", {0.0}}, {"max", {1.0}}});
  float trv[6] = {0, 0, 0, 0, 0.2f, 0};
  int aTrV = accessor(buf.add(trv, sizeof trv, views), 5126, 2, "VEC3");

  json g;
  g["asset"] = {{"version", "2.0"}, {"generator", "animorph tests"}};
  g["scene"] = 0;
  g["scenes"] = json::array({{{"nodes", {0, 1}}}});
  g["nodes"] = json::array({{{"name", "Body"}, {"mesh", 0}, {"skin", 0}},
                            {{"name", "Armature"}, {"children", {2}}},
                            {{"name", "hip"}, {"children", {3}}},
                            {{"name", "spine"}, {"translation", {0.0, 1.0, 0.0}}}});
  g["meshes"] = json::array({{{"name", "BodyMesh"},
                              {"primitives", json::array({{{"attributes",
                                                            {{"POSITION", aPos},
                                                             {"NORMAL", aNrm},
                                                             {"JOINTS_0", aJnt},
                                                             {"WEIGHTS_0", aWgt}}},
                                                           {"indices", aIdx}}})}}});
  g["skins"] = json::array({{{"name", "Skin"}, {"joints", {2, 3}}, {"inverseBindMatrices", aIbm}, {"skeleton", 2}}});
  g["animations"] = json::array(
      {{{"name", "wave"},
        {"samplers", json::array({{{"input", aRotT}, {"output", aRotV}, {"interpolation", "LINEAR"}},
                                  {{"input", aTrT}, {"output", aTrV}, {"interpolation", "LINEAR"}}})},
        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 3}, {"path", "rotation"}}}},
                                  {{"sampler", 1}, {"target", {{"node", 2}, {"path", "translation"}}}}})}}});
  g["bufferViews"] = views;
  g["accessors"] = accessors;
  g["buffers"] = json::array({{{"byteLength", buf.bytes().size()},
                               {"uri", "data:application/octet-stream;base64," + base64(buf.bytes())}}});
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << g.dump(1);
  if (!f) throw std::runtime_error("cannot write " + path);
  return c;
}

}  // namespace animorph::test
