#pragma once
// Textured characters for the material tests: a 2x2 image of four known colours
// (each with its own alpha), written as PNG or JPEG, and a glTF quad that shows
// it, so imports, renders and weight maps can be checked at known texels.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace animorph::test {

// The 2x2 texture, rows top to bottom: red, green / blue, yellow; alphas 255, 170, 85, 0.
inline constexpr std::array<std::array<uint8_t, 4>, 4> kQuadTexels = {{
    {{255, 0, 0, 255}}, {{0, 255, 0, 170}}, {{0, 0, 255, 85}}, {{255, 255, 0, 0}}}};

// Encodes width x height RGBA8 pixels (rows top to bottom) as a PNG / a JPEG (quality 95,
// no alpha) in memory. Empty on failure.
std::vector<uint8_t> encodePng(int width, int height, const std::vector<uint8_t>& rgba);
std::vector<uint8_t> encodeJpeg(int width, int height, const std::vector<uint8_t>& rgba);
// kQuadTexels as a flat RGBA8 buffer.
std::vector<uint8_t> quadTexelBytes();

struct TexturedQuadOptions {
  enum class Image { PngFile, JpegFile, Embedded, CorruptFile, Missing } image = Image::PngFile;
  glm::vec4 factor{1.0f};         // baseColorFactor
  bool nearest = true;            // sampler NEAREST/NEAREST (else LINEAR), wrap CLAMP_TO_EDGE
  bool textureTransform = false;  // KHR_texture_transform: offset (0.5, 0), scale (0.5, 1)
  bool secondPrimitive = false;   // a second quad beside it (x + 2.5) with an untextured blue material
};

// Writes dir/quad.gltf (its buffer embedded, + the texture file): a 2 x 2 m quad in the z = 0 plane
// facing +z, corners (-1, -1) .. (1, 1), uv (0, 0) at its top-left corner (-1, 1) and (1, 1)
// at (1, -1), so each texel covers one quarter. Returns the .gltf path.
std::string writeTexturedQuad(const std::string& dir, const TexturedQuadOptions& options = {});

}  // namespace animorph::test
