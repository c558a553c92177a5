#include "core/doc/weight_map_command.h"

#include <algorithm>

namespace animorph {
namespace {

class WeightMapCommand final : public Command {
 public:
  WeightMapCommand(std::string actorId, bool addsEntry, std::vector<float> before, std::vector<float> after,
                   std::string label)
      : actorId_(std::move(actorId)), addsEntry_(addsEntry), before_(std::move(before)), after_(std::move(after)),
        label_(std::move(label)) {}
  void apply(Project& p) override {
    ActorMorph* a = p.morph.findActor(actorId_);
    if (!a && addsEntry_) {
      p.morph.actors.push_back(ActorMorph{});
      a = &p.morph.actors.back();
      a->actorId = actorId_;
    }
    if (a) a->weightMap = after_;
  }
  void revert(Project& p) override {
    if (addsEntry_) {
      std::erase_if(p.morph.actors, [&](const ActorMorph& a) { return a.actorId == actorId_; });
      return;
    }
    if (ActorMorph* a = p.morph.findActor(actorId_)) a->weightMap = before_;
  }
  std::string label() const override { return label_; }

 private:
  std::string actorId_;
  bool addsEntry_;
  std::vector<float> before_, after_;
  std::string label_;
};

}  // namespace

Result<std::unique_ptr<Command>> setWeightMapCommand(const Project& p, const std::string& actorId,
                                                     std::vector<float> after, std::string label) {
  const ActorMorph* am = p.morph.findActor(actorId);
  const bool inMorph = actorId == p.morph.sourceActorId || actorId == p.morph.targetActorId;
  if (!am && !inMorph)
    return Error{"actor '" + actorId + "' is not part of the project's morph (only its source and target have weight maps)"};
  for (size_t i = 0; i < after.size(); ++i)
    if (!(after[i] >= 0.0f && after[i] <= 1.0f))
      return Error{"weight map of '" + actorId + "': value " + std::to_string(i) + " is outside [0, 1]"};
  return std::unique_ptr<Command>(std::make_unique<WeightMapCommand>(
      actorId, am == nullptr, am ? am->weightMap : std::vector<float>{}, std::move(after), std::move(label)));
}

}  // namespace animorph
