#include "core/blobtree/blob_tree_json.h"

#include <limits>

#include "core/anim/track_json.h"
#include "core/blobtree/validate.h"
#include "core/util/atomic_file.h"
#include "core/util/json_text.h"

namespace animorph {

using nlohmann::json;

namespace {

json paramToJson(const ParamValue& v) {
  if (auto* f = std::get_if<FloatTrack>(&v)) return trackToJson(*f);
  if (auto* p = std::get_if<Vec3Track>(&v)) return trackToJson(*p);
  if (auto* q = std::get_if<QuatTrack>(&v)) return trackToJson(*q);
  json arr = json::array();
  for (const auto& t : std::get<ControlPoints>(v)) arr.push_back(trackToJson(t));
  return arr;
}

json nodeToJson(const BlobNode& n) {
  json j;
  j["id"] = n.id;
  j["type"] = nodeTypeInfo(n.type).name;
  if (!n.name.empty()) j["name"] = n.name;
  const auto& specs = nodeTypeInfo(n.type).params;
  if (!specs.empty()) {
    json p = json::object();
    for (size_t i = 0; i < specs.size() && i < n.params.size(); ++i) {
      // A colour left at the default is not written: a tree without colours saves as it did before
      // primitives carried colour (and reads back with the default).
      if (isColorParam(specs[i]) && n.params[i] == ParamValue(Vec3Track(specs[i].defaultValue))) continue;
      p[specs[i].name] = paramToJson(n.params[i]);
    }
    j["params"] = p;
  }
  if (!n.children.empty()) {
    json c = json::array();
    for (const auto& ch : n.children) c.push_back(nodeToJson(ch));
    j["children"] = c;
  }
  return j;
}

// `path` locates nodes whose id is not known yet ("root.children[2]");
// `depth` is the node's level (the root is 1).
Result<BlobNode> nodeFromJson(const json& j, const std::string& path, int depth) {
  if (!j.is_object()) return Error{path + ": a node must be a JSON object"};
  if (!j.contains("id")) return Error{path + ": node without an integer \"id\""};
  std::string why;
  auto readId = jsonInteger(j["id"], std::numeric_limits<int>::min(), std::numeric_limits<int>::max(), why);
  if (!readId) return Error{path + ": \"id\": " + why};
  const int id = static_cast<int>(*readId);
  std::string who = "node " + std::to_string(id);
  if (!j.contains("type") || !j["type"].is_string()) return Error{who + ": missing \"type\""};
  std::string typeName = j["type"].get<std::string>();
  const NodeTypeInfo* info = findNodeType(typeName);
  if (!info) return Error{who + ": unknown node type '" + typeName + "'"};
  std::string name;
  if (j.contains("name")) {
    if (!j["name"].is_string()) return Error{who + ": \"name\" must be a string"};
    name = j["name"].get<std::string>();
  }
  BlobNode n = makeBlobNode(info->type, id, name);
  who = describeNode(n);
  if (depth > kMaxBlobTreeDepth)
    return Error{who + ": nested " + std::to_string(depth) + " nodes deep, more than the " +
                 std::to_string(kMaxBlobTreeDepth) + " allowed"};
  static const json kNoParams = json::object();
  const json& params = j.contains("params") ? j["params"] : kNoParams;
  if (!params.is_object()) return Error{who + ": \"params\" must be an object"};
  for (auto it = params.begin(); it != params.end(); ++it)
    if (paramIndex(info->type, it.key()) < 0) return Error{who + ": unknown parameter '" + it.key() + "'"};
  for (size_t i = 0; i < info->params.size(); ++i) {
    const ParamSpec& spec = info->params[i];
    if (!params.contains(spec.name)) {
      if (spec.required) return Error{who + ": missing parameter '" + std::string(spec.name) + "'"};
      continue;
    }
    const json& pj = params[spec.name];
    std::string where = who + ": parameter '" + spec.name + "'";
    switch (spec.kind) {
      case ParamKind::Float: {
        auto t = floatTrackFromJson(pj, where);
        if (!t) return Error{t.error()};
        n.params[i] = std::move(*t);
        break;
      }
      case ParamKind::Vec3: {
        auto t = vec3TrackFromJson(pj, where);
        if (!t) return Error{t.error()};
        n.params[i] = std::move(*t);
        break;
      }
      case ParamKind::Quat: {
        auto t = quatTrackFromJson(pj, where);
        if (!t) return Error{t.error()};
        n.params[i] = std::move(*t);
        break;
      }
      case ParamKind::Vec3List: {
        if (!pj.is_array()) return Error{where + ": expected an array of points (each a vector track)"};
        ControlPoints pts;
        for (size_t k = 0; k < pj.size(); ++k) {
          auto t = vec3TrackFromJson(pj[k], where + " point " + std::to_string(k));
          if (!t) return Error{t.error()};
          pts.push_back(std::move(*t));
        }
        n.params[i] = std::move(pts);
        break;
      }
    }
  }
  if (j.contains("children")) {
    const json& c = j["children"];
    if (!c.is_array()) return Error{who + ": \"children\" must be an array"};
    for (size_t k = 0; k < c.size(); ++k) {
      auto ch = nodeFromJson(c[k], who + " child " + std::to_string(k), depth + 1);
      if (!ch) return Error{ch.error()};
      n.children.push_back(std::move(*ch));
    }
  }
  return n;
}

}  // namespace

json blobTreeToJson(const BlobTree& tree) {
  return json{{"threshold", trackToJson(tree.threshold)}, {"root", nodeToJson(tree.root)}};
}

json blobTreeSceneToJson(const BlobTree& tree) {
  json j = {{"format", "animorph-blobtree"}, {"version", kBlobTreeFormatVersion}};
  json body = blobTreeToJson(tree);
  j["threshold"] = body["threshold"];
  j["root"] = body["root"];
  return j;
}

std::string blobTreeSceneToString(const BlobTree& tree) { return blobTreeSceneToJson(tree).dump(1) + "\n"; }

Result<BlobTree> blobTreeFromJson(const json& j, const std::string& source) {
  if (!j.is_object()) return Error{source + ": a BlobTree must be a JSON object"};
  if (j.contains("format")) {
    if (j["format"] != "animorph-blobtree")
      return Error{source + ": \"format\" is " + j["format"].dump() + ", expected \"animorph-blobtree\""};
    if (!j.contains("version")) return Error{source + ": \"version\" missing or not an integer"};
    std::string why;
    auto readVersion =
        jsonInteger(j["version"], std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max(), why);
    if (!readVersion) return Error{source + ": \"version\": " + why};
    const long long v = *readVersion;
    if (v > kBlobTreeFormatVersion)
      return Error{source + ": version " + std::to_string(v) + " is newer than this Animorph reads (" +
                   std::to_string(kBlobTreeFormatVersion) + "); update Animorph"};
    if (v < 1) return Error{source + ": version " + std::to_string(v) + " is not valid"};
  }
  BlobTree tree;
  if (j.contains("threshold")) {
    auto t = floatTrackFromJson(j["threshold"], "threshold");
    if (!t) return Error{source + ": " + t.error()};
    tree.threshold = std::move(*t);
  }
  if (!j.contains("root")) return Error{source + ": missing \"root\" node"};
  auto root = nodeFromJson(j["root"], "root", 1);
  if (!root) return Error{source + ": " + root.error()};
  tree.root = std::move(*root);
  if (Status s = validateBlobTree(tree); !s) return Error{source + ": " + s.error()};
  return tree;
}

Result<BlobTree> parseBlobTreeScene(const std::string& text, const std::string& source) {
  auto parsed = parseJsonText(text, source);
  if (!parsed) return Error{parsed.error()};
  const json& j = *parsed;
  if (j.is_object() && j.contains("format") && j["format"] == "animorph") {
    if (!j.contains("blobtree")) return Error{source + ": project has no \"blobtree\" key"};
    return blobTreeFromJson(j["blobtree"], source + ": blobtree");
  }
  return blobTreeFromJson(j, source);
}

Result<BlobTree> loadBlobTreeScene(const std::string& path) {
  auto text = readFile(path);
  if (!text) return Error{text.error()};
  return parseBlobTreeScene(*text, path);
}

Status saveBlobTreeScene(const BlobTree& tree, const std::string& path) {
  return writeFileAtomic(path, blobTreeSceneToString(tree));
}

}  // namespace animorph
