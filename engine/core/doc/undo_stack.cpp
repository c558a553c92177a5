#include "core/doc/undo_stack.h"

namespace animorph {

void UndoStack::push(Project& p, std::unique_ptr<Command> cmd) {
  cmd->apply(p);
  if (merging_ && mergeTarget_ >= 0 && mergeTarget_ + 1 == static_cast<long>(index_) &&
      commands_[mergeTarget_]->mergeWith(*cmd)) {
    if (cleanIndex_ == static_cast<long>(index_)) cleanIndex_ = -1;
    return;
  }
  if (index_ < commands_.size()) {
    commands_.erase(commands_.begin() + static_cast<long>(index_), commands_.end());
    if (cleanIndex_ > static_cast<long>(index_)) cleanIndex_ = -1;
  }
  commands_.push_back(std::move(cmd));
  index_ = commands_.size();
  if (merging_) mergeTarget_ = static_cast<long>(index_) - 1;
  if (commands_.size() > limit_) {
    commands_.erase(commands_.begin());
    --index_;
    if (mergeTarget_ >= 0) --mergeTarget_;
    cleanIndex_ = cleanIndex_ > 0 ? cleanIndex_ - 1 : -1;
  }
}

bool UndoStack::undo(Project& p) {
  if (!canUndo()) return false;
  commands_[--index_]->revert(p);
  mergeTarget_ = -1;
  return true;
}

bool UndoStack::redo(Project& p) {
  if (!canRedo()) return false;
  commands_[index_++]->apply(p);
  mergeTarget_ = -1;
  return true;
}

std::string UndoStack::undoLabel() const { return canUndo() ? commands_[index_ - 1]->label() : std::string(); }
std::string UndoStack::redoLabel() const { return canRedo() ? commands_[index_]->label() : std::string(); }

void UndoStack::clear() {
  commands_.clear();
  index_ = 0;
  cleanIndex_ = 0;
  mergeTarget_ = -1;
}

}  // namespace animorph
