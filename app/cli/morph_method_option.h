#pragma once
// The morph method options of `new` and `bake`: --method M (interpolation,
// space_time, skeleton_correspondence) and --correspondence-blend B
// (interpolation, space_time: how skeleton correspondence combines its two
// in-between stand-ins).
#include <optional>
#include <string>
#include <vector>

#include "core/project/morph_setup.h"

namespace animorph::cli {

struct MorphMethodOptions {
  std::optional<MorphMethod> method;
  std::optional<MorphMethod> correspondenceBlend;
};

// When args[i] is one of the options, reads it and its value (advancing i)
// and returns true; error is set when the value is missing or unknown.
bool readMorphMethodOption(const std::vector<std::string>& args, size_t& i, MorphMethodOptions& out,
                           std::string& error);

// Sets the options given on m.
void applyMorphMethodOptions(const MorphMethodOptions& o, MorphSetup& m);

}  // namespace animorph::cli
