#include "core/scene/scene_frame.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/blobtree/tree_edit.h"
#include "core/rig/pose.h"
#include "core/rig/skinning.h"

namespace animorph {

void LazyBlobGuides::add(const std::string& actorId, const BlobTree& tree, double timeSec, const glm::mat4& model) {
  sources_.push_back({actorId, &tree, timeSec, model});
  built_.reset();
}

const std::vector<BlobGuides>& LazyBlobGuides::get() const {
  if (!built_) {
    built_.emplace();
    built_->reserve(sources_.size());
    for (const Source& s : sources_) {
      built_->push_back(blobGuides(*s.tree, s.timeSec, s.model));
      built_->back().actorId = s.actorId;
    }
  }
  return *built_;
}

namespace {

void addActor(SceneFrame& out, const Actor& actor, std::shared_ptr<const Character> ch, double timeSec) {
  const Character& c = *ch;
  const AnimationClip* clip = nullptr;
  float t = 0.0f;
  if (!c.clips.empty()) {
    clip = &c.clips[static_cast<size_t>(std::clamp(actor.clip, 0, static_cast<int>(c.clips.size()) - 1))];
    t = static_cast<float>(actorClipTimeSec(actor, *clip, timeSec));
  }
  const glm::mat4 actorM = actor.transform.matrix();
  const auto globals = poseGlobals(c, clip, t);
  for (int node : c.meshNodes()) {
    MeshDraw d;
    d.actorId = actor.id;
    d.character = ch;
    d.meshNode = node;
    d.meshIndex = c.nodes[node].mesh;
    d.model = actorM * globals[node];
    d.joints = jointMatrices(c, node, globals);
    d.morphWeights = morphWeightsAt(c, node, clip, t);
    out.meshes.push_back(std::move(d));
  }
  // Skeleton overlay: every joint of every skin, linked to its parent when
  // the parent is a joint too.
  std::vector<char> isJoint(c.nodes.size(), 0);
  for (const Skin& s : c.skins)
    for (int j : s.joints)
      if (j >= 0 && j < static_cast<int>(c.nodes.size())) isJoint[j] = 1;
  for (size_t j = 0; j < c.nodes.size(); ++j) {
    if (!isJoint[j]) continue;
    glm::vec3 tail = glm::vec3(actorM * globals[j][3]);
    out.jointPositions.push_back(tail);
    int parent = c.nodes[j].parent;
    if (parent >= 0 && isJoint[parent]) {
      BoneDraw b;
      b.actorId = actor.id;
      b.node = static_cast<int>(j);
      b.head = glm::vec3(actorM * globals[parent][3]);
      b.tail = tail;
      out.bones.push_back(b);
    }
  }
}

}  // namespace

SceneFrame evaluateScene(const Project& project, const std::string& baseDir, AssetCache& assets, double timeSec) {
  namespace fs = std::filesystem;
  SceneFrame out;
  out.timeSec = timeSec;
  for (const Actor& actor : project.actors) {
    if (!actor.visible) continue;
    if (actor.kind == ActorKind::BlobTree) {
      BlobDraw d;
      d.actorId = actor.id;
      d.model = actor.transform.matrix();
      d.treeTimeSec = blobActorTimeSec(actor, timeSec);
      out.blobGuides.add(actor.id, actor.blobTree, d.treeTimeSec, d.model);
      out.blobs.push_back(std::move(d));
      continue;
    }
    fs::path p(actor.assetPath);
    std::string abs = (p.is_absolute() ? p : fs::path(baseDir) / p).lexically_normal().string();
    const AssetCache::Entry& e = assets.get(abs);
    if (!e.character) {
      out.errors.push_back("actor '" + actor.id + "': " + e.error);
      continue;
    }
    addActor(out, actor, e.character, timeSec);
  }
  return out;
}

Bounds posedBounds(const SceneFrame& frame, const std::string& actorId) {
  Bounds b;
  std::vector<glm::vec3> pos, nrm;
  for (const MeshDraw& d : frame.meshes) {
    if (!actorId.empty() && d.actorId != actorId) continue;
    skinMesh(d.character->meshes[d.meshIndex], d.joints, pos, nrm, d.morphWeights);
    for (const auto& p : pos) b.add(glm::vec3(d.model * glm::vec4(p, 1.0f)));
  }
  return b;
}

}  // namespace animorph
