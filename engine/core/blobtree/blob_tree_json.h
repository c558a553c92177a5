#pragma once
// BlobTree JSON. A scene file is
//   {"format": "animorph-blobtree", "version": 1, "threshold": TRACK, "root": NODE}
// and the same object without "format"/"version" can sit inside a project
// under a "blobtree" key. NODE = {"id": int, "type": name, "name": str,
// "params": {name: TRACK | [TRACK...]}, "children": [NODE...]}; see docs/blobtree.md.
#include <string>

#include <nlohmann/json.hpp>

#include "core/blobtree/blob_tree.h"
#include "core/util/result.h"

namespace animorph {

inline constexpr int kBlobTreeFormatVersion = 1;
// Deepest chain of nodes a BlobTree read from JSON may have (the root is
// level 1); deeper trees are refused, naming the first node too deep.
inline constexpr int kMaxBlobTreeDepth = 64;

// {"threshold", "root"}: the embeddable form.
nlohmann::json blobTreeToJson(const BlobTree& tree);
// The scene file form (embeddable form plus "format" and "version").
nlohmann::json blobTreeSceneToJson(const BlobTree& tree);
std::string blobTreeSceneToString(const BlobTree& tree);

// Parses either form and validates the tree. Errors start with `source`, then
// name the node id and the reason (unknown node type, missing parameter, NaN,
// negative radius, q < 1, ...). Newer versions are refused.
Result<BlobTree> blobTreeFromJson(const nlohmann::json& j, const std::string& source);
Result<BlobTree> parseBlobTreeScene(const std::string& text, const std::string& source);

// Reads a scene file, or a project (*.animorph) holding a "blobtree" key.
Result<BlobTree> loadBlobTreeScene(const std::string& path);
// Writes a scene file atomically.
Status saveBlobTreeScene(const BlobTree& tree, const std::string& path);

}  // namespace animorph
