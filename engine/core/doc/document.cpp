#include "core/doc/document.h"

#include <cstdlib>
#include <algorithm>
#include <filesystem>

#include "core/util/atomic_file.h"
#include "core/project/project_io.h"

namespace animorph {
namespace fs = std::filesystem;

Document::Document() = default;

Result<std::unique_ptr<Document>> Document::open(const std::string& path, JobProgress* progress) {
  auto p = loadProject(path, progress);
  if (!p) return Error{p.error()};
  auto doc = std::make_unique<Document>();
  doc->reset(std::move(*p), fs::absolute(path).lexically_normal().string());
  return doc;
}

void Document::reset(Project p, std::string path) {
  project_ = std::move(p);
  path_ = std::move(path);
  history_.clear();
  recovered_ = false;
  selection = {};
  ++revision_;
  autosavedRevision_ = revision_;
  lastAutosaveSec_ = changesSeenSec_ = -1.0;
}

void Document::execute(std::unique_ptr<Command> cmd) {
  history_.push(project_, std::move(cmd));
  ++revision_;
}

bool Document::undo() {
  if (!history_.undo(project_)) return false;
  ++revision_;
  return true;
}

bool Document::redo() {
  if (!history_.redo(project_)) return false;
  ++revision_;
  return true;
}

void Document::setCurrentFrame(int frame) { project_.timeline.currentFrame = frame; }

std::string Document::displayName() const {
  return path_.empty() ? std::string("untitled") : fs::path(path_).filename().string();
}

std::string Document::baseDir() const {
  return path_.empty() ? fs::current_path().string() : fs::path(path_).parent_path().string();
}

std::string Document::resolveAsset(const std::string& assetPath) const {
  fs::path p(assetPath);
  if (p.is_absolute()) return p.lexically_normal().string();
  return (fs::path(baseDir()) / p).lexically_normal().string();
}

Status Document::save() {
  if (path_.empty()) return Error{"untitled project: choose a file name with Save As"};
  return saveAs(path_);
}

Status Document::saveAs(const std::string& path) {
  std::string abs = fs::absolute(path).lexically_normal().string();
  // Asset paths are stored relative to the project; re-base them when the
  // project moves to another directory.
  Project out = project_;
  std::string newDir = fs::path(abs).parent_path().string();
  for (Actor& a : out.actors) {
    fs::path resolved = resolveAsset(a.assetPath);
    a.assetPath = fs::path(resolved).lexically_relative(newDir).generic_string();
    if (a.assetPath.empty()) a.assetPath = resolved.generic_string();
  }
  Status st = saveProject(out, abs);
  if (!st) return st;
  std::string oldAutosave = autosavePath();
  project_ = std::move(out);
  path_ = abs;
  history_.markClean();
  recovered_ = false;
  autosavedRevision_ = revision_;
  lastAutosaveSec_ = changesSeenSec_ = -1.0;  // the next edit gets its first autosave soon again
  std::error_code ec;
  fs::remove(oldAutosave, ec);
  fs::remove(autosavePath(), ec);
  return Status::success();
}

std::string Document::autosavePath() const {
  if (!path_.empty()) return path_ + ".autosave";
  const char* home = std::getenv("HOME");
  fs::path dir = fs::path(home ? home : "/tmp") / ".local/share/animorph";
  return (dir / "untitled.animorph.autosave").string();
}

bool Document::autosaveIfDue(double nowSec, double intervalSec) {
  if (revision_ == autosavedRevision_ || !dirty()) {
    changesSeenSec_ = -1.0;
    return false;
  }
  if (changesSeenSec_ < 0.0) changesSeenSec_ = nowSec;
  if (nowSec - changesSeenSec_ < std::min(intervalSec, kFirstAutosaveDelaySec)) return false;
  if (lastAutosaveSec_ >= 0.0 && nowSec - lastAutosaveSec_ < intervalSec) return false;
  lastAutosaveSec_ = nowSec;
  std::string target = autosavePath();
  std::error_code ec;
  fs::create_directories(fs::path(target).parent_path(), ec);
  Project out = project_;
  // Keep asset paths valid relative to the autosave's directory (the same
  // directory as the project, or the absolute path for untitled projects).
  if (path_.empty())
    for (Actor& a : out.actors) a.assetPath = resolveAsset(a.assetPath);
  if (!saveProject(out, target)) return false;
  autosavedRevision_ = revision_;
  return true;
}

bool Document::hasNewerAutosave(const std::string& path) {
  std::error_code ec;
  fs::path a = path + ".autosave";
  if (!fs::exists(a, ec)) return false;
  if (!fs::exists(path, ec)) return true;
  // File times tick coarsely (a few ms): an autosave written just after a
  // save can carry the same time. Saving removes the autosave, so one that
  // is not older than the project was written after it.
  return fs::last_write_time(a, ec) >= fs::last_write_time(path, ec);
}

Result<std::unique_ptr<Document>> Document::recoverAutosave(const std::string& path, JobProgress* progress) {
  auto p = loadProject(path + ".autosave", progress);
  if (!p) return Error{p.error()};
  auto doc = std::make_unique<Document>();
  doc->reset(std::move(*p), fs::absolute(path).lexically_normal().string());
  doc->recovered_ = true;  // unsaved until the user saves it
  return doc;
}

}  // namespace animorph
