#include "core/doc/actor_removal.h"

#include <algorithm>

namespace animorph {

std::unique_ptr<Command> deleteActorCommand(const Project& p, const std::string& actorId) {
  auto it = std::find_if(p.actors.begin(), p.actors.end(), [&](const Actor& a) { return a.id == actorId; });
  if (it == p.actors.end()) return nullptr;
  Actor saved = *it;
  MorphSetup savedMorph = p.morph;
  size_t index = static_cast<size_t>(it - p.actors.begin());
  return std::make_unique<LambdaCommand>(
      "Delete " + saved.name,
      [actorId](Project& proj) {
        auto& v = proj.actors;
        v.erase(std::remove_if(v.begin(), v.end(), [&](const Actor& a) { return a.id == actorId; }), v.end());
        MorphSetup& m = proj.morph;
        if (m.sourceActorId == actorId || m.targetActorId == actorId)
          m = MorphSetup{};
        else
          std::erase_if(m.actors, [&](const ActorMorph& a) { return a.actorId == actorId; });
      },
      [saved, savedMorph, index](Project& proj) {
        auto& v = proj.actors;
        v.insert(v.begin() + static_cast<long>(std::min(index, v.size())), saved);
        proj.morph = savedMorph;
      });
}

}  // namespace animorph
