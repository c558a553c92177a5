#pragma once
// An 8-bit RGBA image in host memory (read back from a render target) and PNG output.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/util/result.h"

namespace animorph::gpu {

struct RgbaImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> pixels;  // rows top to bottom, 4 bytes per pixel (r, g, b, a)

  // The pixel at (x, y) as 0..255 values; (0,0,0,0) outside the image.
  glm::u8vec4 at(uint32_t x, uint32_t y) const;
};

// Writes image as a PNG file. Errors: empty image, file not writable (the message names the path).
Status writePng(const std::string& path, const RgbaImage& image);

}  // namespace animorph::gpu
