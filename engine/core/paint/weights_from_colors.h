#pragma once
// Weight maps from a glTF character's vertex colours (COLOR_0): an artist can
// paint the map in another tool as vertex colours and bring it in.
#include <optional>
#include <string>
#include <vector>

#include "core/rig/character.h"
#include "core/util/result.h"

namespace animorph {

enum class ColorChannel { Red, Luminance, Alpha };

const char* colorChannelName(ColorChannel c);  // "red", "luminance", "alpha"
// Parses "red" / "color" / "colour" (red), "luminance", "alpha"; nullopt otherwise.
std::optional<ColorChannel> parseColorChannel(const std::string& text);

// One weight per vertex over c.meshNodes() (the weight-map layout) from the
// chosen channel of COLOR_0, clamped to [0, 1] (luminance: Rec. 709 weights of
// RGB). Meshes without colours get 0. Errors (naming the character's file):
// no mesh drawn by the character has COLOR_0.
Result<std::vector<float>> weightMapFromVertexColors(const Character& c, ColorChannel channel);

}  // namespace animorph
