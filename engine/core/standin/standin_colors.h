#pragma once
// The stand-in's colours (docs/morph.md, "Colour through the morph"): every segment carries the
// colours of the surface it approximates as kSegmentColorSamples samples along its length
// (SegmentColors, standin/standin.h), sampled from the character's vertices closest to it. A point
// of the implicit surface takes the field-weighted blend of the nearby segments' colours
// (field/surface_color.h): for that, the colour program splits every segment into one
// sub-segment per sample, each carrying its sample. A convolution segment's field is the integral
// of the kernel along it, so its parts' fields sum to the whole segment's: each part's field
// contribution is exactly the weight its colour gets, and the colour varies smoothly along the
// segment. (A capsule union's parts give the same field too; a capsule blend's parts only weigh the
// colours.) A profile along the length, not a texture: limbs and bodies change colour along their
// bones far more than around them, and four samples cost 48 bytes a segment and no mapping.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/standin/standin.h"

namespace animorph {

// One SegmentColors per segment of segs (posed in the same space as positions): each vertex goes
// to the segment whose capsule surface (distance to the axis minus the radius) is closest to it,
// and to the sample of its projection's place along that segment; a sample is the mean of its
// vertices' colours (linear RGB of colors[i]). A sample without vertices takes its nearest
// sampled neighbour's on the segment; a segment without vertices the mean of all the vertices.
// Empty segs or n == 0: every segment unset.
std::vector<SegmentColors> sampleSegmentColors(const std::vector<PosedSegment>& segs, const glm::vec3* positions,
                                               const glm::vec4* colors, size_t n);

// The segment index each vertex goes to by sampleSegmentColors' rule (-1: no segment).
std::vector<int> closestSegments(const std::vector<PosedSegment>& segs, const glm::vec3* positions, size_t n);

// segs with every coloured segment split into kSegmentColorSamples equal parts (same radius and
// weight scale), part k carrying sample k as its only colour; uncoloured segments and segments too
// short to split (parts under kMinSegmentLength) are kept whole. For colour programs only (see
// above): the field is the same, the primitives four times as many.
std::vector<PosedSegment> splitSegmentsForColor(const std::vector<PosedSegment>& segs);

}  // namespace animorph
