#pragma once
// Characters loaded from the files (glTF, FBX, Collada, OBJ: io/character_import.h) that a project's actors reference,
// keyed by absolute path. Loads once, reloads when the file changes on disk,
// remembers failures (with their message) so the UI can show them.
#include <map>
#include <memory>
#include <string>

#include "core/rig/character.h"

namespace animorph {

class AssetCache {
 public:
  struct Entry {
    std::shared_ptr<const Character> character;  // null when loading failed
    std::string error;                           // why loading failed
    long long mtime = 0;
  };

  // Loads the entry of absolutePath without the cache: safe on any thread (a background job loads
  // a project's characters with it; the UI thread then insert()s them).
  static Entry load(const std::string& absolutePath);
  // Adds (or replaces) an entry loaded elsewhere.
  void insert(const std::string& absolutePath, Entry e) { entries_[absolutePath] = std::move(e); }
  bool contains(const std::string& absolutePath) const { return entries_.count(absolutePath) != 0; }
  // Every entry, by absolute path (a copy of the cache used off the UI thread is merged back with it).
  const std::map<std::string, Entry>& entries() const { return entries_; }

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
