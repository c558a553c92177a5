#pragma once
// How baked frames are named on disk, and how a set of them appears at once: a sequence is
// written under temporary names and renamed when it is complete, so a cancelled or failed bake
// leaves no half-written files behind.
#include <string>
#include <vector>

#include "core/util/result.h"

namespace animorph {

// DIR/NAME_####.EXT: the frame number padded to 4 digits, as Houdini's $F4 and Blender's
// mesh-sequence readers expect.
std::string frameFileName(const std::string& dir, const std::string& name, int frame, const char* ext);

// Where an output path chosen in a project points: relative paths are taken from baseDir (the
// project's folder); "" stays "".
std::string resolveOutputPath(const std::string& output, const std::string& baseDir);

// A file-name prefix from a project name: characters outside [A-Za-z0-9._-] become '_'; "frame"
// for an empty name.
std::string framePrefix(const std::string& name);

// Files written under a temporary name (FINAL.part-PID) and renamed to their final names together
// by commit(); the destructor (without commit) removes the temporaries.
class StagedFiles {
 public:
  StagedFiles() = default;
  ~StagedFiles();
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;

  // Where to write the file that is to become finalPath (recorded for commit()).
  std::string stage(const std::string& finalPath);
  // Renames every staged file to its final name (replacing what was there). A folder at a final
  // name is refused before any rename (nothing renamed, every temporary removed); on a failed
  // rename the error names the file and the temporaries not yet renamed are removed.
  Status commit();
  // Removes the staged files now.
  void discard();

 private:
  std::vector<std::pair<std::string, std::string>> files_;  // (temporary, final)
  bool committed_ = false;
};

}  // namespace animorph
