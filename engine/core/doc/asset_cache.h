#pragma once
// Characters loaded from the glTF files that a project's actors reference,
// keyed by absolute path. Loads once, reloads when the file changes on disk,
// remembers failures (with their message) so the UI can show them.
#include <map>
#include <memory>
#include <string>

#include "rig/character.h"

namespace animorph {

class AssetCache {
 public:
  struct Entry {
    std::shared_ptr<const Character> character;  // null when loading failed
    std::string error;                           // why loading failed
    long long mtime = 0;
  };

  // The character at absolutePath, loading it if needed. Never throws.
  const Entry& get(const std::string& absolutePath);
  // Forgets everything (next get() reloads).
  void clear() { entries_.clear(); }
  // Reloads entries whose file changed; returns how many changed.
  int refresh();

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace animorph
