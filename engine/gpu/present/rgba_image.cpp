#include "gpu/present/rgba_image.h"

#include <stb_image_write.h>  // implementation from Debian's libstb

namespace animorph::gpu {

glm::u8vec4 RgbaImage::at(uint32_t x, uint32_t y) const {
  if (x >= width || y >= height) return glm::u8vec4(0);
  const uint8_t* p = &pixels[(size_t(y) * width + x) * 4];
  return {p[0], p[1], p[2], p[3]};
}

Status writePng(const std::string& path, const RgbaImage& image) {
  if (image.width == 0 || image.height == 0 || image.pixels.size() < size_t(image.width) * image.height * 4)
    return Error{path + ": no image to write"};
  int ok = stbi_write_png(path.c_str(), int(image.width), int(image.height), 4, image.pixels.data(),
                          int(image.width * 4));
  if (!ok) return Error{path + ": cannot write PNG (directory missing or not writable?)"};
  return Status::success();
}

}  // namespace animorph::gpu
