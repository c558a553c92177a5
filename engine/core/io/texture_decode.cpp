// The one file of the core that calls stb_image and stb_image_write (Debian's libstb ships
// them compiled: libstb.so).
#include "core/io/texture_decode.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <climits>
#include <filesystem>
#include <memory>

#include "core/util/atomic_file.h"

namespace animorph {

namespace fs = std::filesystem;

Result<TextureImage> decodeTextureImage(const unsigned char* bytes, size_t size, const std::string& name) {
  if (!bytes || size == 0) return Error{name + ": cannot decode: the image is empty"};
  if (size > size_t(INT_MAX)) return Error{name + ": cannot decode: the file is larger than 2 GiB"};
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes, int(size), &w, &h, &comp)) {
    const char* why = stbi_failure_reason();
    return Error{name + ": cannot decode: " + (why ? why : "not an image stb_image reads")};
  }
  if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide || size_t(w) * size_t(h) > kMaxTexturePixels)
    return Error{name + ": " + std::to_string(w) + " x " + std::to_string(h) +
                 " pixels is over the texture budget (at most " + std::to_string(kMaxTextureSide) +
                 " on a side and " + std::to_string(kMaxTexturePixels / (1024 * 1024)) + " Mpixels)"};
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(bytes, int(size), &w, &h, &comp, 4),
                                                   stbi_image_free);
  if (!pixels) {
    const char* why = stbi_failure_reason();
    return Error{name + ": cannot decode: " + (why ? why : "unknown reason")};
  }
  TextureImage t;
  t.name = name;
  t.width = w;
  t.height = h;
  t.rgba = std::make_shared<const std::vector<uint8_t>>(pixels.get(), pixels.get() + size_t(w) * size_t(h) * 4);
  return t;
}

Result<TextureImage> loadTextureFile(const std::string& baseDir, const std::string& uri) {
  const std::string label = "texture '" + uri + "'";
  if (uri.empty()) return Error{label + ": empty path"};
  fs::path rel(uri);
  if (rel.is_absolute() || rel.has_root_name() || uri[0] == '/' || uri[0] == '\\')
    return Error{label + ": absolute paths are not allowed (textures must lie in the character file's folder)"};
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(fs::absolute(baseDir, ec), ec);
  const fs::path full = fs::weakly_canonical(dir / rel, ec);
  if (ec) return Error{label + ": cannot resolve: " + ec.message()};
  auto d = dir.begin();
  auto q = full.begin();
  for (; d != dir.end(); ++d, ++q)
    if (q == full.end() || *q != *d) return Error{label + ": resolves outside the character file's folder"};
  if (!fs::is_regular_file(full, ec)) return Error{label + ": file not found (" + full.string() + ")"};
  auto bytes = readFile(full.string());
  if (!bytes) return Error{label + ": " + bytes.error()};
  return decodeTextureImage(reinterpret_cast<const unsigned char*>(bytes->data()), bytes->size(), uri);
}

std::vector<uint8_t> encodeTexturePng(const TextureImage& t) {
  std::vector<uint8_t> out;
  if (!t.valid()) return out;
  auto append = [](void* context, void* data, int size) {
    auto* o = static_cast<std::vector<uint8_t>*>(context);
    o->insert(o->end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &out, t.width, t.height, 4, t.rgba->data(), t.width * 4)) out.clear();
  return out;
}

}  // namespace animorph
