#pragma once
// An undoable edit of the project. Commands change only the Project; every
// edit a panel or tool makes goes through one.
#include <functional>
#include <memory>
#include <string>

#include "core/project/project.h"

namespace animorph {

class Command {
 public:
  virtual ~Command() = default;
  virtual void apply(Project& p) = 0;
  virtual void revert(Project& p) = 0;
  virtual std::string label() const = 0;
  // Commands with the same non-empty mergeKey, pushed one after another while
  // a merge is open (a drag), fold into one undo step. Returns true if other
  // (already applied) was absorbed into this command.
  virtual bool mergeWith(const Command& /*other*/) { return false; }
  virtual std::string mergeKey() const { return {}; }
};

// Sets one value reached through an accessor. The accessor may return null
// when its target no longer exists (then apply/revert do nothing).
template <class T>
class SetValueCommand final : public Command {
 public:
  using Accessor = std::function<T*(Project&)>;
  SetValueCommand(std::string label, Accessor access, T before, T after, std::string mergeKey = {})
      : label_(std::move(label)), access_(std::move(access)), before_(std::move(before)),
        after_(std::move(after)), mergeKey_(std::move(mergeKey)) {}
  void apply(Project& p) override {
    if (T* v = access_(p)) *v = after_;
  }
  void revert(Project& p) override {
    if (T* v = access_(p)) *v = before_;
  }
  std::string label() const override { return label_; }
  std::string mergeKey() const override { return mergeKey_; }
  bool mergeWith(const Command& other) override {
    auto* o = dynamic_cast<const SetValueCommand<T>*>(&other);
    if (!o || mergeKey_.empty() || o->mergeKey_ != mergeKey_) return false;
    after_ = o->after_;
    return true;
  }

 private:
  std::string label_;
  Accessor access_;
  T before_, after_;
  std::string mergeKey_;
};

// Generic command from two closures; for structural edits (add/remove actor).
class LambdaCommand final : public Command {
 public:
  using Fn = std::function<void(Project&)>;
  LambdaCommand(std::string label, Fn apply, Fn revert)
      : label_(std::move(label)), apply_(std::move(apply)), revert_(std::move(revert)) {}
  void apply(Project& p) override { apply_(p); }
  void revert(Project& p) override { revert_(p); }
  std::string label() const override { return label_; }

 private:
  std::string label_;
  Fn apply_, revert_;
};

// Builds a command that sets an actor's field (found by id) to value.
template <class T>
std::unique_ptr<Command> setActorField(const Project& p, const std::string& actorId, T Actor::*field, T value,
                                       std::string label, std::string mergeKey = {}) {
  const Actor* a = p.findActor(actorId);
  T before = a ? a->*field : value;
  return std::make_unique<SetValueCommand<T>>(
      std::move(label),
      [actorId, field](Project& proj) -> T* {
        Actor* act = proj.findActor(actorId);
        return act ? &(act->*field) : nullptr;
      },
      std::move(before), std::move(value), std::move(mergeKey));
}

}  // namespace animorph
