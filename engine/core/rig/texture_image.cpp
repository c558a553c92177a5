#include "core/rig/texture_image.h"

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

}  // namespace

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
