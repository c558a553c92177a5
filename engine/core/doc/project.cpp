#include "doc/project.h"

namespace animorph {

Actor* Project::findActor(const std::string& id) {
  for (auto& a : actors)
    if (a.id == id) return &a;
  return nullptr;
}

const Actor* Project::findActor(const std::string& id) const {
  for (const auto& a : actors)
    if (a.id == id) return &a;
  return nullptr;
}

std::string Project::uniqueActorId(const std::string& base) const {
  std::string stem = base.empty() ? std::string("actor") : base;
  if (!findActor(stem)) return stem;
  for (int i = 2;; ++i) {
    std::string id = stem + "_" + std::to_string(i);
    if (!findActor(id)) return id;
  }
}

}  // namespace animorph
