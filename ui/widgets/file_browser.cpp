#include "ui/widgets/file_browser.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "ui/widgets/widget_rects.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {
std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string expandHome(const std::string& p) {
  if (p.empty() || p[0] != '~') return p;
  const char* home = std::getenv("HOME");
  if (!home) return p;
  if (p.size() == 1) return home;
  if (p[1] == '/') return std::string(home) + p.substr(1);
  return p;
}

std::string humanSize(std::uintmax_t b) {
  char buf[32];
  if (b < 1024) std::snprintf(buf, sizeof buf, "%ju B", b);
  else if (b < 1024 * 1024) std::snprintf(buf, sizeof buf, "%.1f KiB", b / 1024.0);
  else std::snprintf(buf, sizeof buf, "%.1f MiB", b / (1024.0 * 1024.0));
  return buf;
}
}  // namespace

bool matchesExtensions(const std::string& name, const std::vector<std::string>& extensions) {
  if (extensions.empty()) return true;
  std::string n = lower(name);
  for (const std::string& e : extensions)
    if (n.size() > e.size() && n.compare(n.size() - e.size(), e.size(), e) == 0) return true;
  return false;
}

Result<std::vector<DirEntry>> listDirectory(const std::string& dir, const std::vector<std::string>& extensions) {
  std::error_code ec;
  fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) return Error{dir + ": cannot list directory: " + ec.message()};
  std::vector<DirEntry> out;
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) return Error{dir + ": cannot list directory: " + ec.message()};
    std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code sec;
    bool isDir = it->is_directory(sec);
    if (!isDir && !matchesExtensions(name, extensions)) continue;
    DirEntry e;
    e.name = name;
    e.isDir = isDir;
    if (!isDir) {
      auto sz = it->file_size(sec);
      e.sizeBytes = sec ? 0 : sz;
    }
    out.push_back(std::move(e));
  }
  std::sort(out.begin(), out.end(), [](const DirEntry& a, const DirEntry& b) {
    if (a.isDir != b.isDir) return a.isDir;
    std::string la = lower(a.name), lb = lower(b.name);
    return la != lb ? la < lb : a.name < b.name;
  });
  return out;
}

void FileBrowser::open(Mode mode, std::string title, std::vector<FileFilter> filters, std::string startDir,
                       std::string defaultName) {
  mode_ = mode;
  title_ = std::move(title);
  filters_ = std::move(filters);
  if (filters_.empty()) filters_.push_back({"All files", {}});
  filter_ = 0;
  error_.clear();
  overwritePath_.clear();
  selectedName_.clear();
  field_ = std::move(defaultName);
  std::error_code ec;
  std::string start = expandHome(startDir);
  if (start.empty() || !fs::is_directory(start, ec)) start = fs::current_path(ec).string();
  dir_ = fs::absolute(start, ec).lexically_normal().string();
  if (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
  refresh();
  pendingOpen_ = true;
  focusField_ = true;
}

void FileBrowser::close() {
  open_ = false;
  pendingOpen_ = false;
  overwritePath_.clear();
}

void FileBrowser::refresh() {
  auto list = listDirectory(dir_, filters_[filter_].extensions);
  if (list) {
    entries_ = std::move(*list);
  } else {
    entries_.clear();
    error_ = list.error();
  }
}

void FileBrowser::navigate(const std::string& dir) {
  std::error_code ec;
  fs::path p = fs::path(expandHome(dir));
  if (p.is_relative()) p = fs::path(dir_) / p;
  p = p.lexically_normal();
  std::string s = p.string();
  if (s.size() > 1 && s.back() == '/') s.pop_back();
  if (!fs::is_directory(s, ec)) {
    error_ = s + ": not a directory";
    return;
  }
  auto list = listDirectory(s, filters_[filter_].extensions);
  if (!list) {
    error_ = list.error();
    return;
  }
  dir_ = s;
  entries_ = std::move(*list);
  error_.clear();
  selectedName_.clear();
}

void FileBrowser::navigateUp() {
  fs::path parent = fs::path(dir_).parent_path();
  if (!parent.empty() && parent.string() != dir_) navigate(parent.string());
}

void FileBrowser::setFilter(int index) {
  if (index < 0 || index >= static_cast<int>(filters_.size())) return;
  filter_ = index;
  refresh();
}

std::optional<std::string> FileBrowser::finish(const std::string& path) {
  close();
  return path;
}

std::optional<std::string> FileBrowser::submit(const std::string& text) {
  std::string typed = text;
  while (!typed.empty() && std::isspace(static_cast<unsigned char>(typed.back()))) typed.pop_back();
  while (!typed.empty() && std::isspace(static_cast<unsigned char>(typed.front()))) typed.erase(0, 1);
  if (typed.empty()) {
    error_ = mode_ == Mode::Open ? "type or choose a file to open" : "type a file name";
    return std::nullopt;
  }
  fs::path p = fs::path(expandHome(typed));
  if (p.is_relative()) p = fs::path(dir_) / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (fs::is_directory(p, ec)) {
    navigate(p.string());
    if (error_.empty()) field_.clear();
    return std::nullopt;
  }
  const auto& exts = filters_[filter_].extensions;
  if (mode_ == Mode::Open) {
    if (!fs::exists(p, ec)) {
      error_ = p.string() + ": no such file";
      return std::nullopt;
    }
    if (!fs::is_regular_file(p, ec)) {
      error_ = p.string() + ": not a regular file";
      return std::nullopt;
    }
    return finish(p.string());
  }
  // Save: add the filter's extension, check the directory, confirm overwrites.
  if (!exts.empty() && !matchesExtensions(p.filename().string(), exts)) p += exts.front();
  fs::path parent = p.parent_path();
  if (!fs::is_directory(parent, ec)) {
    error_ = parent.string() + ": no such directory";
    return std::nullopt;
  }
  if (p.filename().empty()) {
    error_ = "type a file name";
    return std::nullopt;
  }
  if (fs::exists(p, ec)) {
    overwritePath_ = p.string();
    openOverwritePopup_ = true;
    return std::nullopt;
  }
  return finish(p.string());
}

std::optional<std::string> FileBrowser::confirmOverwrite(bool yes) {
  std::string path = overwritePath_;
  overwritePath_.clear();
  if (!yes || path.empty()) return std::nullopt;
  return finish(path);
}

std::optional<std::string> FileBrowser::draw() {
  if (!open_ && !pendingOpen_) return std::nullopt;
  std::string popupId = title_ + "##file_browser";
  if (pendingOpen_) {
    ImGui::OpenPopup(popupId.c_str());
    pendingOpen_ = false;
    open_ = true;
  }
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowSize(ImVec2(std::min(720.0f, io.DisplaySize.x * 0.9f), std::min(480.0f, io.DisplaySize.y * 0.8f)),
                           ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(popupId.c_str(), nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    // Closed by ImGui (should not happen without a close button): reset.
    open_ = false;
    return std::nullopt;
  }
  std::optional<std::string> result;

  if (ImGui::Button("Up")) navigateUp();
  noteWidget("file_browser/up");
  ImGui::SameLine();
  ImGui::TextUnformatted(dir_.c_str());
  if (filters_.size() > 1) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(220.0f);
    if (ImGui::BeginCombo("##filter", filters_[filter_].label.c_str())) {
      for (int i = 0; i < static_cast<int>(filters_.size()); ++i)
        if (ImGui::Selectable(filters_[i].label.c_str(), i == filter_)) setFilter(i);
      ImGui::EndCombo();
    }
  }

  float footer = ImGui::GetFrameHeightWithSpacing() * 2.0f + ImGui::GetTextLineHeightWithSpacing();
  ImGui::BeginChild("##entries", ImVec2(0.0f, -footer), true);
  std::string enterDir;
  for (const DirEntry& e : entries_) {
    std::string label = e.isDir ? e.name + "/" : e.name;
    bool selected = !e.isDir && e.name == selectedName_;
    if (e.isDir) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.55f, 0.75f, 1.0f, 1.0f));
    bool clicked = ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_AllowDoubleClick);
    if (e.isDir) ImGui::PopStyleColor();
    noteWidget("file_browser/entry/" + e.name);
    if (!e.isDir) {
      ImGui::SameLine(ImGui::GetWindowContentRegionMax().x - 90.0f);
      ImGui::TextDisabled("%s", humanSize(e.sizeBytes).c_str());
    }
    if (clicked) {
      bool dbl = ImGui::IsMouseDoubleClicked(0);
      if (e.isDir) {
        if (dbl) enterDir = e.name;
      } else {
        selectedName_ = e.name;
        field_ = e.name;
        if (dbl) result = submit(e.name);
      }
    }
  }
  ImGui::EndChild();
  if (!enterDir.empty()) navigate(enterDir);

  if (focusField_) {
    ImGui::SetKeyboardFocusHere();
    focusField_ = false;
  }
  ImGui::SetNextItemWidth(-190.0f);
  bool entered = ImGui::InputText("##path", &field_, ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
  noteWidget("file_browser/path");
  if (entered) {
    result = submit(field_);
    focusField_ = !result && overwritePath_.empty();  // keep typing after an error
  }
  ImGui::SameLine();
  if (ImGui::Button(mode_ == Mode::Open ? "Open" : "Save", ImVec2(80.0f, 0.0f))) result = submit(field_);
  noteWidget("file_browser/ok");
  ImGui::SameLine();
  bool cancel = ImGui::Button("Cancel", ImVec2(80.0f, 0.0f));
  noteWidget("file_browser/cancel");
  if (!ImGui::IsAnyItemActive() && overwritePath_.empty() && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
    cancel = true;
  if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.35f, 1.0f), "%s", error_.c_str());

  // Overwrite confirmation, nested in the browser's modal.
  if (openOverwritePopup_) {
    ImGui::OpenPopup("Overwrite?##file_browser");
    openOverwritePopup_ = false;
  }
  if (ImGui::BeginPopupModal("Overwrite?##file_browser", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s already exists.\nReplace it?", overwritePath_.c_str());
    if (ImGui::Button("Replace", ImVec2(100.0f, 0.0f))) {
      result = confirmOverwrite(true);
      ImGui::CloseCurrentPopup();
    }
    noteWidget("file_browser/overwrite_yes");
    ImGui::SameLine();
    if (ImGui::Button("Cancel##overwrite", ImVec2(100.0f, 0.0f))) {
      confirmOverwrite(false);
      focusField_ = true;
      ImGui::CloseCurrentPopup();
    }
    noteWidget("file_browser/overwrite_no");
    ImGui::EndPopup();
  }

  if (cancel && !result) close();
  if (!open_) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return result;
}

}  // namespace animorph
