#pragma once
// The correspondence graph G(A -> B) of an animorphosis (docs/design.md §5,
// docs/animorphosis.md): links between node ids of a source BlobTree A and a
// target BlobTree B, at any level. A link may carry its own s(u) curve that
// drives its whole sub-tree unless a deeper link carries another one. Plain
// data: validateCorrespondence checks it against the two trees,
// buildGenericTree turns it into the generic tree C.
#include <optional>
#include <string>
#include <vector>

#include "core/anim/track.h"
#include "core/util/result.h"

namespace animorph {

struct CorrespondenceLink {
  int nodeA = 0;                        // node id in the source tree A
  int nodeB = 0;                        // node id in the target tree B
  std::optional<FloatTrack> sOverride;  // s(u), u in [0, 1], s(0) = 0, s(1) = 1; none: inherited
  float confidence = 1.0f;              // in [0, 1]; automatic links: how sure the matcher was
  bool artist = true;                   // drawn by the artist; automatic correspondence never changes these
  bool operator==(const CorrespondenceLink&) const = default;
};

struct CorrespondenceGraph {
  std::vector<CorrespondenceLink> links;
  // Links the automatic correspondence proposed below its confidence threshold:
  // shown to the artist, not applied (buildGenericTree and the validation ignore
  // them) until accepted (doc/animorphosis_commands.h).
  std::vector<CorrespondenceLink> suggestions;

  // Index of the link nodeA -> nodeB, or -1.
  int find(int nodeA, int nodeB) const;
  // Indices of the links that touch node `id` of A (or of B).
  std::vector<int> linksOfA(int id) const;
  std::vector<int> linksOfB(int id) const;
  // Index of the suggestion nodeA -> nodeB, or -1.
  int findSuggestion(int nodeA, int nodeB) const;
  bool operator==(const CorrespondenceGraph&) const = default;
};

// The default global s(u): a smoothstep ramp from (0, 0) to (1, 1).
FloatTrack defaultSCurve();

// Checks an s curve: finite keys with times in [0, 1], the first key at
// (0, 0), the last at (1, 1). Errors start with `where`.
Status checkSCurve(const FloatTrack& s, const std::string& where);

// s at u, with s = 0 for u <= 0 and 1 for u >= 1, clamped to [0, 1] in between
// (a Hermite curve may overshoot; intensities and slerps stay in range).
float evaluateS(const FloatTrack& s, double u);

}  // namespace animorph
