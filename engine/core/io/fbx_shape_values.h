#pragma once
// The rest values of FBX blend shape channels (their DeformPercent), read from the file's own
// bytes: assimp 5.2 parses them but gives every blend shape of one geometry per channel the weight
// 1, so the importer reads them here and maps them onto assimp's shapes by channel name.
// Binary FBX: a bounded walk over the node records (offsets checked against their parent and the
// file, nesting capped at kFbxMaxDepth, arrays skipped unread); ASCII FBX: the channels' blocks.
#include <map>
#include <string>
#include <vector>

#include "core/util/result.h"

namespace animorph {

inline constexpr int kFbxMaxDepth = 32;

struct FbxShapeValues {
  // Channel name (as assimp names its shapes: without the "SubDeformer::" class) -> percent (0-100).
  std::map<std::string, double> percentByChannel;
  // Names that two channels give different values: their first value is kept.
  std::vector<std::string> conflicting;
};

// Reads the BlendShapeChannel deformers of a binary or ASCII FBX document (file: the path as
// given, for messages). A channel's value is its Properties70 "DeformPercent" when it has one,
// else its DeformPercent record. A file without channels gives an empty map. Fails naming file,
// the record's byte offset and the reason when a record leaves its parent or the file, a
// property runs past its record, or the nesting is deeper than kFbxMaxDepth.
Result<FbxShapeValues> readFbxShapeValues(const std::string& file, const std::string& bytes);

}  // namespace animorph
