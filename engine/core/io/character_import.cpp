#include "core/io/character_import.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/io/assimp_import.h"
#include "core/io/gltf_import.h"
#include "core/util/atomic_file.h"

namespace animorph {

namespace {

std::string lowerExtension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return e;
}

std::string extensionList() {
  std::string out;
  const auto& all = characterFileExtensions();
  for (size_t i = 0; i < all.size(); ++i) out += (i == 0 ? "" : i + 1 == all.size() ? " or " : ", ") + all[i];
  return out;
}

}  // namespace

CharacterFormat characterFormatOf(const std::string& path) {
  const std::string e = lowerExtension(path);
  if (e == ".gltf" || e == ".glb") return CharacterFormat::Gltf;
  if (e == ".fbx") return CharacterFormat::Fbx;
  if (e == ".dae") return CharacterFormat::Collada;
  if (e == ".obj") return CharacterFormat::Obj;
  if (e == ".animorph" || e == ".json") return CharacterFormat::Unknown;
  return isGltfPath(path) ? CharacterFormat::Gltf : CharacterFormat::Unknown;
}

bool isCharacterPath(const std::string& path) { return characterFormatOf(path) != CharacterFormat::Unknown; }

const std::vector<std::string>& characterFileExtensions() {
  static const std::vector<std::string> all = {".gltf", ".glb", ".fbx", ".dae", ".obj"};
  return all;
}

Result<Character> importCharacter(const std::string& path) {
  switch (characterFormatOf(path)) {
    case CharacterFormat::Gltf: {
      auto c = importGltf(path);
      if (c) c->format = "glTF";
      return c;
    }
    case CharacterFormat::Fbx:
    case CharacterFormat::Collada:
    case CharacterFormat::Obj: return importAssimp(path);
    case CharacterFormat::Unknown: break;
  }
  // A path that is not a regular file gets readFile's reason ("is a character device", "no such
  // file"); it refuses such files before reading a byte.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    if (auto r = readFile(path); !r) return Error{r.error()};
  return Error{path + ": not a character file of a known format (expected " + extensionList() + ")"};
}

}  // namespace animorph
