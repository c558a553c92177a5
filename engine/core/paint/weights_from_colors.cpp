#include "core/paint/weights_from_colors.h"

#include <algorithm>
#include <filesystem>

namespace animorph {

const char* colorChannelName(ColorChannel c) {
  switch (c) {
    case ColorChannel::Red: return "red";
    case ColorChannel::Luminance: return "luminance";
    case ColorChannel::Alpha: return "alpha";
  }
  return "?";
}

std::optional<ColorChannel> parseColorChannel(const std::string& text) {
  if (text == "red" || text == "color" || text == "colour") return ColorChannel::Red;
  if (text == "luminance") return ColorChannel::Luminance;
  if (text == "alpha") return ColorChannel::Alpha;
  return std::nullopt;
}

Result<std::vector<float>> weightMapFromVertexColors(const Character& c, ColorChannel channel) {
  std::vector<float> out;
  bool any = false;
  for (int node : c.meshNodes()) {
    const Mesh& m = c.meshes[c.nodes[node].mesh];
    if (m.colors.size() != m.vertexCount()) {
      out.insert(out.end(), m.vertexCount(), 0.0f);
      continue;
    }
    any = true;
    for (const glm::vec4& col : m.colors) {
      float v = channel == ColorChannel::Red         ? col.r
                : channel == ColorChannel::Alpha     ? col.a
                                                     : 0.2126f * col.r + 0.7152f * col.g + 0.0722f * col.b;
      out.push_back(std::clamp(v, 0.0f, 1.0f));
    }
  }
  if (!any) {
    std::string file = c.sourcePath.empty() ? std::string("the character")
                                            : std::filesystem::path(c.sourcePath).filename().string();
    return Error{file + ": no vertex colours (COLOR_0) in any mesh; nothing to import a weight map from"};
  }
  return out;
}

}  // namespace animorph
