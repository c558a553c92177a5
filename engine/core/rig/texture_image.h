#pragma once
// A decoded texture of a character (a material's base colour texture): RGBA8
// pixels, row 0 at the top (glTF's uv (0, 0)), and the sampler the file gives it
// (wrap per axis, magnification / minification filter). Its mipmap chain comes from
// textureMipLevels (the renderer samples minified textures through it). Decoded by
// io/texture_decode.h; drawn by the renderer (gpu/render/gpu_texture.h) and sampled
// on the CPU by sampleTexture (weight maps from a texture channel).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace animorph {

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureFilter { Linear, Nearest };

struct TextureImage {
  std::string name;  // the file (relative to the character's folder) or "image 3 (embedded)", for messages
  int width = 0, height = 0;
  // width * height * 4 bytes, RGB in sRGB encoding as the file stores it, alpha linear.
  // Shared: a texture and its copies (undo snapshots, the GPU cache) hold one buffer.
  std::shared_ptr<const std::vector<uint8_t>> rgba;
  TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
  TextureFilter magFilter = TextureFilter::Linear, minFilter = TextureFilter::Linear;

  bool valid() const {
    return width > 0 && height > 0 && rgba && rgba->size() == size_t(width) * size_t(height) * 4;
  }
};

// The texel value at uv as the GPU samples it without mipmaps: texel centres at
// ((i + 0.5) / width, (j + 0.5) / height), wrapS / wrapT applied per axis, and
// magFilter's filter (Nearest: the texel containing uv; Linear: bilinear over the
// four nearest texel centres). Returns RGBA in 0..1 as stored (RGB not linearised);
// an invalid texture or a non-finite uv gives (0, 0, 0, 0).
glm::vec4 sampleTexture(const TextureImage& t, glm::vec2 uv);

// One level of a texture's mipmap chain: width * height * 4 bytes laid out as TextureImage::rgba
// (RGB sRGB-encoded, alpha linear).
struct TextureLevel {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

// The mipmap levels below the texture's own: level k + 1 is max(1, floor(size / 2)) of level k
// per axis, down to 1 x 1 (none for a 1 x 1 or invalid texture). Each texel is the mean of the
// 2 x 2 texels of the level above it covers (1 x 2 or 2 x 1 where that axis is already 1; of an
// odd size, the last row or column is left out), averaged in linear light: RGB decoded with the
// sRGB curve (as an R8G8B8A8_SRGB image is sampled), averaged, encoded back and rounded; alpha
// averaged as stored. So a minified texture keeps its mean colour, not a darker one.
std::vector<TextureLevel> textureMipLevels(const TextureImage& t);

// How many levels a full chain of a width x height image has (1 + floor(log2(max side))).
int textureLevelCount(int width, int height);

}  // namespace animorph
