#include "core/doc/actor_commands.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace animorph {
namespace fs = std::filesystem;

std::unique_ptr<Command> addActorCommand(Actor actor) {
  std::string id = actor.id;
  return std::make_unique<LambdaCommand>(
      "Add " + actor.name, [actor](Project& p) { p.actors.push_back(actor); },
      [id](Project& p) {
        auto& v = p.actors;
        v.erase(std::remove_if(v.begin(), v.end(), [&](const Actor& a) { return a.id == id; }), v.end());
      });
}

std::unique_ptr<Command> renameActorCommand(const Project& p, const std::string& actorId, const std::string& name) {
  const Actor* a = p.findActor(actorId);
  if (!a || name.empty() || a->name == name) return nullptr;
  return setActorField(p, actorId, &Actor::name, name, "Rename " + a->name + " to " + name);
}

Actor actorForAsset(const Project& p, const std::string& absoluteAssetPath, const std::string& projectDir) {
  Actor a;
  fs::path asset(absoluteAssetPath);
  std::string stem = asset.stem().string();
  std::string base;
  for (char c : stem) base += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '_';
  a.id = p.uniqueActorId(base.empty() ? "actor" : base);
  a.name = p.uniqueActorName(stem.empty() ? a.id : stem);
  if (!projectDir.empty()) {
    fs::path rel = asset.lexically_relative(projectDir);
    a.assetPath = rel.empty() ? asset.generic_string() : rel.generic_string();
  } else {
    a.assetPath = asset.generic_string();
  }
  return a;
}

}  // namespace animorph
