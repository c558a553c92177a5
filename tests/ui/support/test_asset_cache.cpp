// In-memory AssetCache for the UI tests, linked only while engine/core has no
// implementation of its own (see ../CMakeLists.txt). Characters are
// registered by path (test_character.h); any other path fails to load with
// a message, like a missing file would.
#include "core/project/asset_cache.h"

#include <filesystem>

#include "test_character.h"

namespace animorph {

const AssetCache::Entry& AssetCache::get(const std::string& absolutePath) {
  auto it = entries_.find(absolutePath);
  if (it != entries_.end()) return it->second;
  Entry e;
  if (auto c = test::registeredCharacter(absolutePath)) {
    e.character = c;
  } else if (!std::filesystem::exists(absolutePath)) {
    e.error = absolutePath + ": no such file";
  } else {
    e.error = absolutePath + ": not a registered test character";
  }
  return entries_.emplace(absolutePath, std::move(e)).first->second;
}

int AssetCache::refresh() { return 0; }

}  // namespace animorph
