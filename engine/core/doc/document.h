#pragma once
// The open project: its data, its file, its undo history and its autosave.
// Panels read project() and change it only through execute(); the current
// frame and the selection are view state and bypass the undo stack.
#include <cstdint>
#include <memory>
#include <string>

#include "core/doc/command.h"
#include "core/project/project.h"
#include "core/doc/undo_stack.h"
#include "core/util/job_progress.h"
#include "core/util/result.h"

namespace animorph {

struct Selection {
  std::string actorId;  // empty: nothing selected
  int node = -1;        // a node of that actor's character, or -1 for the actor itself
  int segment = -1;     // with node -1: a segment of that morph actor's stand-in, or -1 for none
  bool operator==(const Selection&) const = default;
};

class Document {
 public:
  Document();

  // Opens a project file. The error names the file and the problem. progress (optional): as
  // loadProject reports it; safe to call off the UI thread (it touches nothing shared).
  static Result<std::unique_ptr<Document>> open(const std::string& path, JobProgress* progress = nullptr);

  const Project& project() const { return project_; }
  // Applies and records an edit.
  void execute(std::unique_ptr<Command> cmd);
  bool undo();
  bool redo();
  UndoStack& history() { return history_; }
  const UndoStack& history() const { return history_; }
  void beginDrag() { history_.beginMerge(); }
  void endDrag() { history_.endMerge(); }

  // Unsaved changes exist.
  bool dirty() const { return recovered_ || !history_.isClean(); }
  // Increments on every change of project data (edits, undo, redo, load).
  uint64_t revision() const { return revision_; }

  // Current frame (view state: not undoable, does not dirty the document).
  void setCurrentFrame(int frame);
  Selection selection;

  const std::string& path() const { return path_; }  // empty while untitled
  std::string displayName() const;
  // Directory that relative asset paths are resolved against.
  std::string baseDir() const;
  // Absolute path of an actor's asset.
  std::string resolveAsset(const std::string& assetPath) const;

  Status save();  // fails if untitled
  Status saveAs(const std::string& path);

  // Autosave file beside the project (or in ~/.local/share/animorph for
  // untitled projects).
  std::string autosavePath() const;
  // Writes the autosave when there are changes since the last save or autosave, once they have
  // waited kFirstAutosaveDelaySec (counted from the first call that sees them: an edit made just
  // before a crash is not lost to a long interval) and at most once every intervalSec after that.
  // intervalSec 0: now. Returns true if it wrote.
  static constexpr double kFirstAutosaveDelaySec = 5.0;
  bool autosaveIfDue(double nowSec, double intervalSec = 60.0);
  // The unsaved changes are all in the autosave already (false when there are none).
  bool autosaveIsCurrent() const { return dirty() && revision_ == autosavedRevision_; }
  // An autosave newer than path exists (offer to recover it).
  static bool hasNewerAutosave(const std::string& path);
  // Loads the autosave of path in place of path (the result is dirty and
  // still saves to path).
  static Result<std::unique_ptr<Document>> recoverAutosave(const std::string& path, JobProgress* progress = nullptr);

  // Replaces the whole project (File > New); clears history.
  void reset(Project p, std::string path);

 private:
  Project project_;
  UndoStack history_;
  std::string path_;
  uint64_t revision_ = 1;
  uint64_t autosavedRevision_ = 1;
  double lastAutosaveSec_ = -1.0;     // when the autosave was last written (-1: not since the last save)
  double changesSeenSec_ = -1.0;      // when autosaveIfDue first saw the unsaved changes (-1: none)
  bool recovered_ = false;
};

}  // namespace animorph
