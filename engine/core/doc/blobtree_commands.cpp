#include "core/doc/blobtree_commands.h"

#include <cctype>

#include "core/blobtree/validate.h"

namespace animorph {

namespace {

class BlobTreeCommand final : public Command {
 public:
  BlobTreeCommand(std::string actorId, BlobTree before, BlobTree after, std::string label, std::string mergeKey)
      : actorId_(std::move(actorId)), before_(std::move(before)), after_(std::move(after)),
        label_(std::move(label)), mergeKey_(std::move(mergeKey)) {}
  void apply(Project& p) override {
    if (Actor* a = p.findActor(actorId_)) a->blobTree = after_;
  }
  void revert(Project& p) override {
    if (Actor* a = p.findActor(actorId_)) a->blobTree = before_;
  }
  std::string label() const override { return label_; }
  std::string mergeKey() const override { return mergeKey_; }
  bool mergeWith(const Command& other) override {
    auto* o = dynamic_cast<const BlobTreeCommand*>(&other);
    if (!o || mergeKey_.empty() || o->mergeKey_ != mergeKey_ || o->actorId_ != actorId_) return false;
    after_ = o->after_;
    return true;
  }

 private:
  std::string actorId_;
  BlobTree before_, after_;
  std::string label_;
  std::string mergeKey_;
};

std::string nodeLabel(const Project& p, const std::string& actorId, int id) {
  const Actor* a = p.findActor(actorId);
  const BlobNode* n = a ? a->blobTree.find(id) : nullptr;
  if (!n) return "node " + std::to_string(id);
  return n->name.empty() ? std::string(nodeTypeInfo(n->type).name) + " " + std::to_string(id) : n->name;
}

std::string paramLabel(const Project& p, const std::string& actorId, const ParamAddress& addr) {
  const Actor* a = p.findActor(actorId);
  const BlobNode* n = a ? a->blobTree.find(addr.node) : nullptr;
  if (!n || addr.param < 0 || addr.param >= int(n->params.size())) return "parameter";
  std::string s = nodeTypeInfo(n->type).params[size_t(addr.param)].name;
  if (addr.point >= 0) s += "[" + std::to_string(addr.point) + "]";
  return s + " of " + nodeLabel(p, actorId, addr.node);
}

}  // namespace

std::unique_ptr<Command> setBlobTreeCommand(const Project& p, const std::string& actorId, BlobTree after,
                                            std::string label, std::string mergeKey) {
  const Actor* a = p.findActor(actorId);
  BlobTree before = a ? a->blobTree : after;
  return std::make_unique<BlobTreeCommand>(actorId, std::move(before), std::move(after), std::move(label),
                                           std::move(mergeKey));
}

Actor makeBlobTreeActor(const Project& p, const std::string& name) {
  Actor a;
  std::string stem;
  for (char c : name.empty() ? std::string("blob") : name)
    stem += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? char(std::tolower(c)) : '_';
  a.id = p.uniqueActorId(stem);
  a.name = p.uniqueActorName(name.empty() ? std::string("Blob") : name);
  a.kind = ActorKind::BlobTree;
  a.blobTree = makeStarterTree();
  return a;
}

Result<std::unique_ptr<Command>> addBlobNodeCommand(const Project& p, const std::string& actorId, int parentId,
                                                    NodeType type, int* newId) {
  int created = -1;
  auto r = editBlobTree(p, actorId, std::string("Add ") + nodeTypeInfo(type).name, [&](BlobTree& t) {
    int next = t.nextId();
    BlobNode n = makeDefaultNode(type, next);
    created = n.id;
    return addNode(t, parentId, std::move(n));
  });
  if (r && newId) *newId = created;
  return r;
}

Result<std::unique_ptr<Command>> deleteBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId) {
  return editBlobTree(p, actorId, "Delete " + nodeLabel(p, actorId, nodeId),
                      [&](BlobTree& t) { return deleteNode(t, nodeId); });
}

Result<std::unique_ptr<Command>> duplicateBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId,
                                                          int* newId) {
  int created = -1;
  auto r = editBlobTree(p, actorId, "Duplicate " + nodeLabel(p, actorId, nodeId), [&](BlobTree& t) -> Status {
    auto id = duplicateNode(t, nodeId);
    if (!id) return Error{id.error()};
    created = *id;
    return Status::success();
  });
  if (r && newId) *newId = created;
  return r;
}

Result<std::unique_ptr<Command>> reparentBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId,
                                                         int newParentId, int index) {
  return editBlobTree(p, actorId,
                      "Move " + nodeLabel(p, actorId, nodeId) + " under " + nodeLabel(p, actorId, newParentId),
                      [&](BlobTree& t) { return reparentNode(t, nodeId, newParentId, index); });
}

Result<std::unique_ptr<Command>> renameBlobNodeCommand(const Project& p, const std::string& actorId, int nodeId,
                                                       const std::string& name) {
  if (name.empty()) return Error{"a node name must not be empty"};
  return editBlobTree(p, actorId, "Rename " + nodeLabel(p, actorId, nodeId) + " to " + name,
                      [&](BlobTree& t) { return renameNode(t, nodeId, name); });
}

Result<std::unique_ptr<Command>> setBlobParamCommand(const Project& p, const std::string& actorId,
                                                     const ParamAddress& a, double timeSec, const ParamSample& value,
                                                     bool key, std::string mergeKey) {
  return editBlobTree(p, actorId, (key ? "Key " : "Set ") + paramLabel(p, actorId, a),
                      [&](BlobTree& t) { return setParamValue(t, a, timeSec, value, key); }, std::move(mergeKey));
}

Result<std::unique_ptr<Command>> deleteBlobKeysCommand(const Project& p, const std::string& actorId,
                                                       const std::vector<KeyRef>& keys) {
  if (keys.empty()) return Error{"no keys selected"};
  return editBlobTree(p, actorId, keysLabel("Delete", keys.size()),
                      [&](BlobTree& t) { return deleteKeys(t, keys); });
}

Result<std::unique_ptr<Command>> moveBlobKeysCommand(const Project& p, const std::string& actorId,
                                                     const BlobTree& original,
                                                     const std::vector<KeyChannelRef>& channels, double dtSec,
                                                     float dValue, std::string mergeKey,
                                                     std::vector<KeyChannelRef>* moved) {
  const Actor* a = p.findActor(actorId);
  if (!a || a->kind != ActorKind::BlobTree) return Error{"no BlobTree actor '" + actorId + "'"};
  if (channels.empty()) return Error{"no keys selected"};
  BlobTree copy = original;
  auto r = moveKeys(copy, channels, dtSec, dValue);
  if (!r) return Error{"actor '" + actorId + "': " + r.error()};
  if (moved) *moved = *r;
  return setBlobTreeCommand(p, actorId, std::move(copy),
                            keysLabel("Move", channels.size()),
                            std::move(mergeKey));
}

Result<std::unique_ptr<Command>> setBlobKeyInterpCommand(const Project& p, const std::string& actorId,
                                                         const std::vector<KeyRef>& keys, KeyInterp interp) {
  if (keys.empty()) return Error{"no keys selected"};
  return editBlobTree(p, actorId, interpLabel(interp),
                      [&](BlobTree& t) { return setKeyInterp(t, keys, interp); });
}

Result<std::unique_ptr<Command>> setBlobKeyTangentModeCommand(const Project& p, const std::string& actorId,
                                                              const std::vector<KeyRef>& keys, bool user) {
  if (keys.empty()) return Error{"no keys selected"};
  return editBlobTree(p, actorId, user ? "User tangents" : "Auto tangents",
                      [&](BlobTree& t) { return setKeyTangentMode(t, keys, user); });
}

Result<std::unique_ptr<Command>> setBlobKeyTangentCommand(const Project& p, const std::string& actorId,
                                                          const BlobTree& original, const KeyChannelRef& k,
                                                          float slopePerSec, std::string mergeKey) {
  const Actor* a = p.findActor(actorId);
  if (!a || a->kind != ActorKind::BlobTree) return Error{"no BlobTree actor '" + actorId + "'"};
  BlobTree copy = original;
  if (Status s = setKeyTangent(copy, k, slopePerSec); !s) return Error{"actor '" + actorId + "': " + s.error()};
  return setBlobTreeCommand(p, actorId, std::move(copy), "Change tangent", std::move(mergeKey));
}

}  // namespace animorph
