#pragma once
// Decoding of texture images (PNG, JPEG, and whatever else Debian's stb_image
// reads: BMP, TGA, GIF's first frame) into RGBA8, bounded: images larger than
// kMaxTextureSide on a side or kMaxTexturePixels in all are refused before
// their pixels are decoded; and PNG encoding of a texture (glTF export).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/rig/texture_image.h"
#include "core/util/result.h"

namespace animorph {

inline constexpr int kMaxTextureSide = 16384;
inline constexpr size_t kMaxTexturePixels = size_t(8192) * 8192;  // 256 MiB of RGBA8

// Decodes an encoded image (the bytes of a PNG / JPEG file) into t (name set to
// `name`, the sampler left at its defaults). Errors: "<name>: cannot decode: <reason>"
// (stb_image's reason: a corrupt or truncated file, an unsupported format), or
// "<name>: W x H pixels is over the texture budget of ...".
Result<TextureImage> decodeTextureImage(const unsigned char* bytes, size_t size, const std::string& name);

// Reads and decodes a texture file given relative to a character file's folder
// (baseDir). The file must stay inside baseDir (no absolute path, no ".." out of it,
// no symbolic link out of it). Errors name uri and the reason: outside the folder,
// not found, unreadable, or decodeTextureImage's.
Result<TextureImage> loadTextureFile(const std::string& baseDir, const std::string& uri);

// The texture's pixels as a PNG file's bytes (RGBA, 8 bits). Empty for an invalid texture.
std::vector<uint8_t> encodeTexturePng(const TextureImage& t);

}  // namespace animorph
