#include "ui/common/prefs.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/json_text.h"

namespace animorph {
namespace fs = std::filesystem;
using json = nlohmann::json;

std::string defaultPreferencesPath() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  fs::path base;
  if (xdg && *xdg && fs::path(xdg).is_absolute()) {
    base = xdg;
  } else {
    const char* home = std::getenv("HOME");
    base = fs::path(home && *home ? home : "/tmp") / ".config";
  }
  return (base / "animorph" / "prefs.json").string();
}

std::string preferencesToJson(const Preferences& p) {
  json j;
  j["layout"] = {{"outlinerWidth", p.outlinerWidth},
                 {"inspectorWidth", p.inspectorWidth},
                 {"timelineHeight", p.timelineHeight},
                 {"editorsHeight", p.editorsHeight},
                 {"editorsSplit", p.editorsSplit}};
  j["camera"] = {{"scheme", p.cameraScheme == CameraScheme::Maya ? "maya" : "blender"},
                 {"otherSchemeToo", p.otherSchemeToo}};
  j["recentFiles"] = p.recentFiles;
  j["autosaveIntervalSec"] = p.autosaveIntervalSec;
  j["previewResolution"] = p.previewResolution;
  j["previewCoarseResolution"] = p.previewCoarseResolution;
  j["previewDevice"] = previewDeviceName(p.previewDevice);
  j["particleView"] = p.particleView;
  return j.dump(2) + "\n";
}

Result<Preferences> preferencesFromJson(const std::string& text, const std::string& sourceName) {
  auto parsed = parseJsonText(text, sourceName);
  if (!parsed) return Error{parsed.error()};
  const json& j = *parsed;
  if (!j.is_object()) return Error{sourceName + ": expected a JSON object"};
  Preferences p;
  std::string err;
  auto fail = [&](const std::string& where, const std::string& why) {
    if (err.empty()) err = sourceName + ": " + where + ": " + why;
  };
  auto number = [&](const json& obj, const char* key, const std::string& where, double def, double lo,
                    double hi) {
    if (!obj.contains(key)) return def;
    const json& v = obj[key];
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      fail(where + "." + key, "expected a finite number");
      return def;
    }
    double d = v.get<double>();
    if (d < lo || d > hi) {
      fail(where + "." + key, "out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      return def;
    }
    return d;
  };
  if (j.contains("layout")) {
    const json& l = j["layout"];
    if (!l.is_object()) {
      fail("layout", "expected an object");
    } else {
      p.outlinerWidth = static_cast<float>(number(l, "outlinerWidth", "layout", p.outlinerWidth, 0, 1e5));
      p.inspectorWidth = static_cast<float>(number(l, "inspectorWidth", "layout", p.inspectorWidth, 0, 1e5));
      p.timelineHeight = static_cast<float>(number(l, "timelineHeight", "layout", p.timelineHeight, 0, 1e5));
      p.editorsHeight = static_cast<float>(number(l, "editorsHeight", "layout", p.editorsHeight, 0, 1e5));
      p.editorsSplit = static_cast<float>(number(l, "editorsSplit", "layout", p.editorsSplit, 0, 1));
    }
  }
  if (j.contains("camera")) {
    const json& c = j["camera"];
    if (!c.is_object()) {
      fail("camera", "expected an object");
    } else {
      if (c.contains("scheme")) {
        const json& s = c["scheme"];
        if (s == "maya") p.cameraScheme = CameraScheme::Maya;
        else if (s == "blender") p.cameraScheme = CameraScheme::Blender;
        else fail("camera.scheme", "expected \"maya\" or \"blender\"");
      }
      if (c.contains("otherSchemeToo")) {
        if (c["otherSchemeToo"].is_boolean()) p.otherSchemeToo = c["otherSchemeToo"].get<bool>();
        else fail("camera.otherSchemeToo", "expected true or false");
      }
    }
  }
  if (j.contains("recentFiles")) {
    const json& r = j["recentFiles"];
    if (!r.is_array()) {
      fail("recentFiles", "expected an array of strings");
    } else {
      for (size_t i = 0; i < r.size(); ++i) {
        if (!r[i].is_string()) {
          fail("recentFiles[" + std::to_string(i) + "]", "expected a string");
          break;
        }
        if (p.recentFiles.size() < kMaxRecentFiles) p.recentFiles.push_back(r[i].get<std::string>());
      }
    }
  }
  p.autosaveIntervalSec = number(j, "autosaveIntervalSec", "", p.autosaveIntervalSec, 0, 86400);
  p.previewResolution = static_cast<int>(number(j, "previewResolution", "", p.previewResolution, 8, 512));
  p.previewCoarseResolution =
      static_cast<int>(number(j, "previewCoarseResolution", "", p.previewCoarseResolution, 8, 512));
  // Older files allowed 8..512: clamp into today's range rather than refuse them.
  p.previewResolution = std::clamp(p.previewResolution, kMinPreviewResolution, kMaxPreviewResolution);
  p.previewCoarseResolution = std::clamp(p.previewCoarseResolution, kMinPreviewResolution, kMaxPreviewResolution);
  if (j.contains("previewDevice")) {
    const json& d = j["previewDevice"];
    if (d == "auto") p.previewDevice = PreviewDevice::Auto;
    else if (d == "gpu") p.previewDevice = PreviewDevice::Gpu;
    else if (d == "cpu") p.previewDevice = PreviewDevice::Cpu;
    else fail("previewDevice", "expected \"auto\", \"gpu\" or \"cpu\"");
  }
  if (j.contains("particleView")) {
    if (j["particleView"].is_boolean()) p.particleView = j["particleView"].get<bool>();
    else fail("particleView", "expected true or false");
  }
  if (!err.empty()) {
    // "prefs.json: .autosaveIntervalSec" reads badly for top-level keys.
    auto pos = err.find(": .");
    if (pos != std::string::npos) err.erase(pos + 2, 1);
    return Error{err};
  }
  return p;
}

Result<Preferences> loadPreferences(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return Preferences{};
  auto text = readFile(path);
  if (!text) return Error{text.error()};
  return preferencesFromJson(*text, path);
}

Status savePreferences(const Preferences& p, const std::string& path) {
  std::error_code ec;
  fs::path dir = fs::path(path).parent_path();
  if (!dir.empty()) {
    fs::create_directories(dir, ec);
    if (ec) return Error{dir.string() + ": cannot create directory: " + ec.message()};
  }
  return writeFileAtomic(path, preferencesToJson(p));
}

void addRecentFile(Preferences& p, const std::string& path) {
  auto& r = p.recentFiles;
  r.erase(std::remove(r.begin(), r.end(), path), r.end());
  r.insert(r.begin(), path);
  if (r.size() > kMaxRecentFiles) r.resize(kMaxRecentFiles);
}

}  // namespace animorph
