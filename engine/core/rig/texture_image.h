#pragma once
// A decoded texture of a character (a material's base colour texture): RGBA8
// pixels, row 0 at the top (glTF's uv (0, 0)), and the sampler the file gives it
// (wrap per axis, magnification / minification filter; no mipmaps). Decoded by
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

}  // namespace animorph
