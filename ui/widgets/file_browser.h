#pragma once
// In-app modal file dialog (no dialog library exists on the platform):
// directory listing (directories first, sorted), up / into directories, an
// extension filter, a typed-path field (a full or relative path + Enter),
// double-click to open, overwrite confirmation when saving, inline errors.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/util/result.h"

namespace animorph {

struct FileFilter {
  std::string label;                    // "Animorph project (*.animorph)"
  std::vector<std::string> extensions;  // lower case with the dot; empty = all files
};

struct DirEntry {
  std::string name;
  bool isDir = false;
  std::uintmax_t sizeBytes = 0;
};

// True if name ends with one of extensions (case-insensitive); empty list matches all.
bool matchesExtensions(const std::string& name, const std::vector<std::string>& extensions);

// Entries of dir: directories first, then files matching extensions, each
// group sorted case-insensitively; hidden (dot) entries skipped. The error
// names the directory and the reason.
Result<std::vector<DirEntry>> listDirectory(const std::string& dir, const std::vector<std::string>& extensions);

class FileBrowser {
 public:
  enum class Mode { Open, Save };

  // Opens the dialog on the next draw(). startDir falls back to the current
  // directory when it does not exist; defaultName pre-fills the path field.
  void open(Mode mode, std::string title, std::vector<FileFilter> filters, std::string startDir,
            std::string defaultName = {});
  // Draws the modal while open (call every frame at the top level of the
  // ImGui ID stack). Returns the chosen absolute path on the frame the user
  // confirms; the dialog is closed then.
  std::optional<std::string> draw();
  bool isOpen() const { return open_ || pendingOpen_; }
  void close();

  // What typing text into the path field and pressing Enter does: a
  // directory is entered; a file is returned (Open: it must exist; Save: the
  // filter's extension is added when missing, and an existing file first asks
  // for confirmation, returning nothing until confirmOverwrite()).
  std::optional<std::string> submit(const std::string& text);
  // Answers the overwrite question; returns the path when confirmed.
  std::optional<std::string> confirmOverwrite(bool yes);

  // Enters dir (errors are shown inline and leave the current directory).
  void navigate(const std::string& dir);
  void navigateUp();
  void setFilter(int index);

  Mode mode() const { return mode_; }
  const std::string& title() const { return title_; }
  const std::string& currentDir() const { return dir_; }
  const std::vector<DirEntry>& entries() const { return entries_; }
  const std::string& error() const { return error_; }
  const std::string& overwritePending() const { return overwritePath_; }
  std::string& pathField() { return field_; }

 private:
  void refresh();
  std::optional<std::string> finish(const std::string& path);

  Mode mode_ = Mode::Open;
  std::string title_;
  std::vector<FileFilter> filters_;
  int filter_ = 0;
  std::string dir_;
  std::vector<DirEntry> entries_;
  std::string field_;
  std::string error_;
  std::string overwritePath_;
  std::string selectedName_;
  bool open_ = false;
  bool pendingOpen_ = false;
  bool focusField_ = false;
  bool openOverwritePopup_ = false;
};

}  // namespace animorph
