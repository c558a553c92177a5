#pragma once
// Linear undo history of Commands over a Project, with merging for drags
// and a clean mark for the dirty flag.
#include <memory>
#include <string>
#include <vector>

#include "core/doc/command.h"

namespace animorph {

class UndoStack {
 public:
  // Applies cmd to p and records it (dropping any redo history). While a
  // merge group is open, a command whose mergeKey equals the previous one's
  // is folded into it.
  void push(Project& p, std::unique_ptr<Command> cmd);
  bool undo(Project& p);
  bool redo(Project& p);
  bool canUndo() const { return index_ > 0; }
  bool canRedo() const { return index_ < commands_.size(); }
  std::string undoLabel() const;
  std::string redoLabel() const;

  // A drag: commands pushed between begin and end with equal mergeKeys
  // become one undo step.
  void beginMerge() { merging_ = true; mergeTarget_ = -1; }
  void endMerge() { merging_ = false; mergeTarget_ = -1; }

  void markClean() { cleanIndex_ = static_cast<long>(index_); }
  bool isClean() const { return cleanIndex_ == static_cast<long>(index_); }
  void clear();
  size_t size() const { return commands_.size(); }
  size_t index() const { return index_; }

 private:
  std::vector<std::unique_ptr<Command>> commands_;
  size_t index_ = 0;      // commands_[0, index_) are applied
  long cleanIndex_ = 0;   // -1 when the clean state is no longer reachable
  bool merging_ = false;
  long mergeTarget_ = -1;
  size_t limit_ = 1000;
};

}  // namespace animorph
