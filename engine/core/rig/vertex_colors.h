#pragma once
// The base colour of each vertex of a character as the viewport draws it at that vertex: the
// material's base colour factor x its base colour texture at the vertex's texture coordinates
// (sRGB texels to linear) x COLOR_0, in linear light. The colours a collapsing vertex starts from
// (standin_morph/transition.h) and the stand-in's colours are sampled from (standin/standin_colors.h);
// meshes without texture coordinates, vertices without a material, texture or COLOR_0 take the
// viewport's grey (kViewportGreySrgb), as the renderer draws them.
#include <vector>

#include <glm/glm.hpp>

#include "core/rig/character.h"

namespace animorph {

// The grey the viewport draws surfaces without a colour in (sRGB; gpu::MeshDraw::color).
inline constexpr glm::vec3 kViewportGreySrgb{0.62f, 0.62f, 0.62f};

// The material each vertex of m is drawn with: that of the first part (Mesh::parts) using it, else
// m.material; -1: none.
std::vector<int> vertexMaterials(const Mesh& m);

// One linear RGBA colour per vertex, concatenated over c.meshNodes() (the order of weight maps and
// stand-in bindings); alpha 1. Empty when no mesh of c has a colour of its own (no material factor
// other than white, no decoded texture, no COLOR_0): such a character is drawn grey and its
// stand-in keeps the clay tone.
std::vector<glm::vec4> characterVertexColors(const Character& c);

}  // namespace animorph
