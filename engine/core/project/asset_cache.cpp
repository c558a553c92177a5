#include "core/project/asset_cache.h"

#include <chrono>
#include <filesystem>

#include "core/io/character_import.h"

namespace animorph {
namespace {

// Modification time in nanoseconds since the file clock's epoch, or -1 when
// the file cannot be stat'ed (so a file that appears later counts as changed).
long long modificationTime(const std::string& path) {
  std::error_code ec;
  auto t = std::filesystem::last_write_time(path, ec);
  if (ec) return -1;
  return static_cast<long long>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count());
}

}  // namespace

AssetCache::Entry AssetCache::load(const std::string& path) {
  AssetCache::Entry e;
  e.mtime = modificationTime(path);
  auto c = importCharacter(path);
  if (c) e.character = std::make_shared<const Character>(std::move(*c));
  else e.error = c.error();
  return e;
}

const AssetCache::Entry& AssetCache::get(const std::string& absolutePath) {
  auto it = entries_.find(absolutePath);
  if (it != entries_.end()) return it->second;
  return entries_.emplace(absolutePath, load(absolutePath)).first->second;
}

int AssetCache::refresh() {
  int changed = 0;
  for (auto& [path, entry] : entries_) {
    if (modificationTime(path) == entry.mtime) continue;
    entry = load(path);
    ++changed;
  }
  return changed;
}

}  // namespace animorph
