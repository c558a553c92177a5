#include "core/paint/weights_from_texture.h"

#include <algorithm>
#include <filesystem>

#include "core/rig/texture_image.h"

namespace animorph {

const char* textureChannelName(TextureChannel c) {
  switch (c) {
    case TextureChannel::Red: return "r";
    case TextureChannel::Green: return "g";
    case TextureChannel::Blue: return "b";
    case TextureChannel::Alpha: return "alpha";
  }
  return "?";
}

std::optional<TextureChannel> parseTextureChannel(const std::string& text) {
  if (text == "r" || text == "red") return TextureChannel::Red;
  if (text == "g" || text == "green") return TextureChannel::Green;
  if (text == "b" || text == "blue") return TextureChannel::Blue;
  if (text == "a" || text == "alpha") return TextureChannel::Alpha;
  return std::nullopt;
}

namespace {

// The texture each vertex of m samples: that of the first part using it (else m.material's); null: none.
std::vector<const TextureImage*> vertexTextures(const Character& c, const Mesh& m) {
  auto textureOf = [&](int material) -> const TextureImage* {
    if (material < 0 || size_t(material) >= c.materials.size()) return nullptr;
    const int t = c.materials[size_t(material)].baseColorTexture;
    return t >= 0 && size_t(t) < c.textures.size() && c.textures[size_t(t)].valid() ? &c.textures[size_t(t)] : nullptr;
  };
  std::vector<const TextureImage*> out(m.vertexCount(), nullptr);
  std::vector<char> seen(m.vertexCount(), 0);
  for (const Mesh::Part& p : m.parts) {
    if (p.firstIndex > m.indices.size() || p.indexCount > m.indices.size() - p.firstIndex) continue;
    const TextureImage* t = textureOf(p.material);
    for (size_t i = p.firstIndex; i < size_t(p.firstIndex) + p.indexCount; ++i) {
      const uint32_t v = m.indices[i];
      if (v < out.size() && !seen[v]) seen[v] = 1, out[v] = t;
    }
  }
  const TextureImage* fallback = textureOf(m.material);
  for (size_t v = 0; v < out.size(); ++v)
    if (!seen[v]) out[v] = fallback;
  return out;
}

}  // namespace

Result<std::vector<float>> weightMapFromTexture(const Character& c, TextureChannel channel) {
  std::vector<float> out;
  bool any = false;
  const int k = channel == TextureChannel::Red ? 0 : channel == TextureChannel::Green ? 1 : channel == TextureChannel::Blue ? 2 : 3;
  for (int node : c.meshNodes()) {
    const Mesh& m = c.meshes[c.nodes[node].mesh];
    if (m.texcoords0.size() != m.vertexCount()) {
      out.insert(out.end(), m.vertexCount(), 0.0f);
      continue;
    }
    const std::vector<const TextureImage*> tex = vertexTextures(c, m);
    for (size_t v = 0; v < m.vertexCount(); ++v) {
      any |= tex[v] != nullptr;
      out.push_back(tex[v] ? std::clamp(sampleTexture(*tex[v], m.texcoords0[v])[k], 0.0f, 1.0f) : 0.0f);
    }
  }
  if (!any) {
    std::string file = c.sourcePath.empty() ? std::string("the character")
                                            : std::filesystem::path(c.sourcePath).filename().string();
    return Error{file + ": no mesh has texture coordinates and a decoded base colour texture; nothing to import a "
                        "weight map from"};
  }
  return out;
}

}  // namespace animorph
