#include "core/project/project.h"

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

std::string Project::uniqueActorName(const std::string& base) const {
  auto taken = [&](const std::string& n) {
    for (const Actor& a : actors)
      if (a.name == n) return true;
    return false;
  };
  if (!taken(base)) return base;
  // "Name 7": count on from 7.
  std::string stem = base;
  int next = 2;
  const size_t space = base.find_last_of(' ');
  if (space != std::string::npos && space + 1 < base.size() && base.size() - space <= 7 &&
      base.find_first_not_of("0123456789", space + 1) == std::string::npos) {
    stem = base.substr(0, space);
    next = std::stoi(base.substr(space + 1)) + 1;
  }
  for (int i = next;; ++i) {
    std::string n = stem + " " + std::to_string(i);
    if (!taken(n)) return n;
  }
}

}  // namespace animorph
