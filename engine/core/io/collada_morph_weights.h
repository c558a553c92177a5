#pragma once
// Collada morph weight animation, read from the document's text beside assimp 5.2: assimp drops a
// <channel> that addresses a morph controller's weights with the controller (io/collada_morphs
// removes the controllers it cannot read), or, for a target without '/', takes it for a mesh channel
// of any node whose id the target contains. Exporters such as Maya's and 3ds Max's (OpenCOLLADA)
// write these channels; Blender 3.4 writes none.
//
// Addressing (Collada 1.4.1 and 1.5 "address syntax": ID, then /SID steps, then one selection:
// (i) an array index, or .member) of a morph's weights read here:
//   CONTROLLER/SID(k)      a morph controller's id and any SID below it (a morph has one animatable
//                          array, its weights), e.g. "Body-morph/MorphWeights(0)";
//   SOURCE(k)              the id of the morph's MORPH_WEIGHT <source> or of its <float_array>,
//                          e.g. "Body-weights(1)" (OpenCOLLADA's form);
//   CONTROLLER-weights(k)  the controller's id with "-weights", whatever the source is called;
// and each without (k): the whole array, every key holding every target's weight (an OUTPUT of
// keys x targets values). A channel's sampler gives the key times (INPUT, seconds), the weights
// (OUTPUT) and the interpolation (INTERPOLATION, per key; LINEAR when absent): STEP holds a value
// until the next key; BEZIER, HERMITE, CARDINAL and BSPLINE keys are taken as linear (their tangents
// are not read; the import report says so).
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/io/collada_morphs.h"
#include "core/util/result.h"

namespace animorph {

// The most merged weight values (keys x targets) one morph's animation may hold.
inline constexpr size_t kMaxColladaWeightKeys = size_t(20) << 20;

// Reads the channels of document b's <library_animations> that address a weight of one of morphs
// (their controllerId, weightSourceId, weightArrayId) and fills each animated morph's
// weightTimesSec / weightKeys / weightsStep; adds report lines to notes. Returns the byte ranges
// [at, end) of the <channel> elements read, which the document for assimp leaves out. Channels
// addressing anything else are left to assimp. A malformed weight channel refuses the file (the
// character's animation would be wrong, not merely incomplete): the error names file, the channel
// (its target as written), its byte offset and the reason -- a sampler or source that is missing,
// an index past the morph's targets, a two-dimensional index or a .member selection, OUTPUT or
// INTERPOLATION counts that disagree with the keys, non-finite values, decreasing key times, an
// interpolation Collada does not define, one target animated by two channels, or more than
// kMaxColladaWeightKeys merged values. Time linear in b's size (each source parsed once) plus the
// merged values written.
Result<std::vector<std::pair<size_t, size_t>>> readColladaMorphWeights(const std::string& file, std::string_view b,
                                                                       std::vector<ColladaMorph>& morphs,
                                                                       std::vector<std::string>& notes);

// Morph m's target k's weight at time t (seconds) from its merged keys (held before the first and
// after the last; STEP or linear between keys), or its default weight when m is not animated.
float colladaMorphWeightAt(const ColladaMorph& m, size_t k, float t);

}  // namespace animorph
