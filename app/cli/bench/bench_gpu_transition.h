#pragma once
// `bench morph --gpu`: the vertex-shader transition beside plain skinning on the GPU.
#include <vector>

#include "app/cli/bench/bench.h"
#include "core/standin_morph/transition.h"
#include "core/rig/character.h"
#include "core/standin/standin.h"

namespace animorph::bench {

// Rows for the GPU transition of character c bound to standin (binding):
// offscreen frames (1280x720) drawing it with the transition pipeline (alpha
// 0.5; alpha 0.84 with every vertex re-projected) and with plain skinning, and
// the compute twin's dispatch time. A row saying why when there is no device.
std::vector<Row> gpuTransitionRows(const Options& opt, const Character& c, const Standin& standin,
                                   const StandinBinding& binding);

}  // namespace animorph::bench
