#include "core/rig/texture_image.h"

#include <algorithm>
#include <cmath>

namespace animorph {
namespace {

// Texel index i (any integer) folded into [0, n) by the wrap mode.
int wrapIndex(int i, int n, TextureWrap w) {
  switch (w) {
    case TextureWrap::ClampToEdge: return i < 0 ? 0 : i >= n ? n - 1 : i;
    case TextureWrap::MirroredRepeat: {
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
    case TextureWrap::Repeat: break;
  }
  int m = i % n;
  return m < 0 ? m + n : m;
}

glm::vec4 texel(const TextureImage& t, int x, int y) {
  const uint8_t* p = t.rgba->data() + (size_t(y) * size_t(t.width) + size_t(x)) * 4;
  return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
}

// sRGB-encoded byte to linear light (the exact sRGB curve, as the GPU decodes _SRGB formats).
float srgbByteToLinear(uint8_t b) {
  const float c = float(b) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

uint8_t linearToSrgbByte(float l) {
  const float c = l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

// The level below `above` (w x h): the mean of the 2 x 2 texels each covers.
TextureLevel halveLevel(const uint8_t* above, int w, int h, const float* toLinear) {
  TextureLevel out;
  out.width = std::max(1, w / 2);
  out.height = std::max(1, h / 2);
  out.rgba.resize(size_t(out.width) * size_t(out.height) * 4);
  const int sx = w > 1 ? 2 : 1, sy = h > 1 ? 2 : 1;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      for (int dy = 0; dy < sy; ++dy)
        for (int dx = 0; dx < sx; ++dx) {
          const uint8_t* p = above + (size_t(y * sy + dy) * size_t(w) + size_t(x * sx + dx)) * 4;
          for (int k = 0; k < 3; ++k) sum[k] += toLinear[p[k]];
          sum[3] += float(p[3]);
        }
      const float n = float(sx * sy);
      uint8_t* q = out.rgba.data() + (size_t(y) * size_t(out.width) + size_t(x)) * 4;
      for (int k = 0; k < 3; ++k) q[k] = linearToSrgbByte(sum[k] / n);
      q[3] = uint8_t(std::lround(sum[3] / n));
    }
  return out;
}

}  // namespace

int textureLevelCount(int width, int height) {
  int levels = 1;
  for (int side = std::max(width, height); side > 1; side /= 2) ++levels;
  return levels;
}

std::vector<TextureLevel> textureMipLevels(const TextureImage& t) {
  std::vector<TextureLevel> levels;
  if (!t.valid()) return levels;
  float toLinear[256];
  for (int b = 0; b < 256; ++b) toLinear[b] = srgbByteToLinear(uint8_t(b));
  levels.reserve(size_t(textureLevelCount(t.width, t.height) - 1));  // no reallocation: `above` stays valid
  const uint8_t* above = t.rgba->data();
  int w = t.width, h = t.height;
  while (w > 1 || h > 1) {
    levels.push_back(halveLevel(above, w, h, toLinear));
    above = levels.back().rgba.data();
    w = levels.back().width;
    h = levels.back().height;
  }
  return levels;
}

glm::vec4 sampleTexture(const TextureImage& t, glm::vec2 uv) {
  if (!t.valid() || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec4(0.0f);
  // Keep the coordinates in a range where float -> int is exact (wrapping is periodic).
  const float fx = float(uv.x * t.width), fy = float(uv.y * t.height);
  if (std::abs(fx) > 1e8f || std::abs(fy) > 1e8f) return glm::vec4(0.0f);
  if (t.magFilter == TextureFilter::Nearest) {
    const int x = wrapIndex(int(std::floor(fx)), t.width, t.wrapS);
    const int y = wrapIndex(int(std::floor(fy)), t.height, t.wrapT);
    return texel(t, x, y);
  }
  const float gx = fx - 0.5f, gy = fy - 0.5f;
  const int x0 = int(std::floor(gx)), y0 = int(std::floor(gy));
  const float ax = gx - float(x0), ay = gy - float(y0);
  const int xa = wrapIndex(x0, t.width, t.wrapS), xb = wrapIndex(x0 + 1, t.width, t.wrapS);
  const int ya = wrapIndex(y0, t.height, t.wrapT), yb = wrapIndex(y0 + 1, t.height, t.wrapT);
  const glm::vec4 top = glm::mix(texel(t, xa, ya), texel(t, xb, ya), ax);
  const glm::vec4 bottom = glm::mix(texel(t, xa, yb), texel(t, xb, yb), ax);
  return glm::mix(top, bottom, ay);
}

}  // namespace animorph
