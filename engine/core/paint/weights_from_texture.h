#pragma once
// Weight maps from a channel of a character's base colour textures: an artist
// paints the map as a texture (often its alpha) and brings it in. Each vertex
// takes the channel sampled at its texture coordinates (Mesh::texcoords0) with
// the texture's own sampler (rig/texture_image.h sampleTexture).
#include <optional>
#include <string>
#include <vector>

#include "core/rig/character.h"
#include "core/util/result.h"

namespace animorph {

enum class TextureChannel { Red, Green, Blue, Alpha };

const char* textureChannelName(TextureChannel c);  // "r", "g", "b", "alpha"
// Parses "r" / "red", "g" / "green", "b" / "blue", "a" / "alpha"; nullopt otherwise.
std::optional<TextureChannel> parseTextureChannel(const std::string& text);

// One weight per vertex over c.meshNodes() (the weight-map layout): the chosen channel,
// 0..1, of the base colour texture of the vertex's material (the first material part
// whose triangles use the vertex; else the mesh's material) at the vertex's texture
// coordinates. Vertices of meshes without texture coordinates, or whose material has
// no decoded texture, get 0. Errors (naming the character's file): no mesh drawn by the
// character has both texture coordinates and a decoded base colour texture.
Result<std::vector<float>> weightMapFromTexture(const Character& c, TextureChannel channel);

}  // namespace animorph
