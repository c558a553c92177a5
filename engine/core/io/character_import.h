#pragma once
// The one entry point for opening a character file, whatever its format: drag and drop,
// File > Open, Import, the asset cache and animorph-cli info / new / fit / weights all call
// importCharacter. It picks the importer by extension: .gltf / .glb -> io/gltf_import.h
// (tinygltf), .fbx / .dae / .obj -> io/assimp_import.h (assimp).
#include <string>
#include <vector>

#include "core/rig/character.h"
#include "core/util/result.h"

namespace animorph {

enum class CharacterFormat { Unknown, Gltf, Fbx, Collada, Obj };

// The format a path names: its extension (any case), or for a file without a known
// extension the GLB magic "glTF" in its first four bytes. Reads at most 4 bytes.
CharacterFormat characterFormatOf(const std::string& path);

// True when path names a character file rather than a project (characterFormatOf knows it).
bool isCharacterPath(const std::string& path);

// The extensions importCharacter reads, lower case with the dot: ".gltf", ".glb", ".fbx",
// ".dae", ".obj" (file dialogs' filters and help texts list these).
const std::vector<std::string>& characterFileExtensions();

// Imports the character at path with the importer of its format; sets Character::format.
// Errors name the path as given, the element and the reason; a regular file of no known format
// is refused with the extensions that are, anything else (a device, a FIFO, a folder, a missing
// file) with why it is not a file.
Result<Character> importCharacter(const std::string& path);

}  // namespace animorph
