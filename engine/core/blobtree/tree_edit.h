#pragma once
// Edits of an animated BlobTree as pure functions on the tree: structure (add,
// delete, duplicate, reparent, rename) and animation (set a parameter at a
// time, delete / move keys, interpolation and tangents). Every edit keeps the
// tree valid (validateBlobTree) or refuses with a message naming the node and
// the reason, leaving the tree unchanged. The editor's undoable commands
// (doc/blobtree_commands.h) wrap these.
#include <string>
#include <variant>
#include <vector>

#include "core/anim/key_edit.h"
#include "core/blobtree/blob_tree.h"
#include "core/util/result.h"

namespace animorph {

// The track at address (a Vec3List point's track when point >= 0), or monostate.
TrackPtr findTrack(BlobTree& tree, const ParamAddress& a);
ConstTrackPtr findTrack(const BlobTree& tree, const ParamAddress& a);

// Scalar channels of a parameter kind: 1 (float) or 3 (vec3, list point, quat as Euler).
int channelCount(ParamKind kind);
// The tree's parameters as a TrackSet for the key edits of anim/key_edit.h
// (errors name the node, float values keep their parameter's rule). The set
// refers to tree: it must outlive the set's use.
TrackSet blobTrackSet(BlobTree& tree);

// Number of keys of the track at address (0 when absent).
int keyCount(const BlobTree& tree, const ParamAddress& a);
// Time and value of a key; false when absent.
bool keyAt(const BlobTree& tree, const KeyRef& k, double& timeSec, ParamSample& value);
// Value of the parameter at timeSec; false when absent.
bool sampleParam(const BlobTree& tree, const ParamAddress& a, double timeSec, ParamSample& value);
// True when the track has two or more keys (its value changes over time).
bool isAnimated(const BlobTree& tree, const ParamAddress& a);

// The parent of node id (null for the root or an unknown id); index receives its position.
BlobNode* findParent(BlobTree& tree, int id, int* index = nullptr);
const BlobNode* findParent(const BlobTree& tree, int id, int* index = nullptr);
// True when `id` is `ancestor` or lies in its subtree.
bool isInSubtree(const BlobNode& ancestor, int id);

// A new node of type with values that make a visible shape of about 0.3 m at
// the origin (required parameters get sizes, not 0); operators, maps and
// meta-primitives get the children they need (spheres), with ids from nextId
// onward (nextId is advanced past every id used).
BlobNode makeDefaultNode(NodeType type, int& nextId);

// A new tree: a blend of one sphere (what "New BlobTree actor" starts with).
BlobTree makeStarterTree();

// Adds node (ids must be unused in tree) as a child of parentId at index (-1:
// last). Refuses an unknown parent, a parent that takes no more children, an
// id clash, or a tree deeper than kMaxBlobTreeDepth (it could not be loaded).
Status addNode(BlobTree& tree, int parentId, BlobNode node, int index = -1);
// Deletes a node and its subtree. Refuses the root and a parent that would
// fall below its minimum number of children.
Status deleteNode(BlobTree& tree, int id);
// Copies a subtree with fresh ids right after the original. Returns the copy's id.
Result<int> duplicateNode(BlobTree& tree, int id);
// Moves node id under newParentId at index (-1: last). Refuses the root, a
// move into the node's own subtree (a cycle), a new parent that takes no more
// children, an old parent that would fall below its minimum and a tree deeper
// than kMaxBlobTreeDepth.
Status reparentNode(BlobTree& tree, int id, int newParentId, int index = -1);
// Renames a node (names may repeat; ids identify nodes).
Status renameNode(BlobTree& tree, int id, const std::string& name);

// Sets a parameter at timeSec. With key = false: an animated parameter (two or
// more keys) gets a key at timeSec (created, or the one there replaced, keeping
// its interpolation); a constant one just takes the value. With key = true
// (the key button) the parameter gets a key at timeSec either way, so keying a
// constant at another time than its single key (time 0 for new parameters)
// animates it. Values are clamped to the parameter's rule (radii >= 0,
// q >= 1, ...); a zero vector where it must be non-zero is refused.
Status setParamValue(BlobTree& tree, const ParamAddress& a, double timeSec, const ParamSample& value, bool key);

// Deletes keys. A track that would lose every key keeps its first one's value
// as a constant.
Status deleteKeys(BlobTree& tree, const std::vector<KeyRef>& keys);

// Moves keys by dtSec in time and, per selected channel, by dValue (the same
// delta for every channel listed; quaternion channels in degrees). A moved key
// landing on an unmoved key's time replaces it. Keys whose time would go below
// 0 stop at 0. Returns the channel refs of the moved keys after re-sorting
// (the selection follows its keys), in the order given.
Result<std::vector<KeyChannelRef>> moveKeys(BlobTree& tree, const std::vector<KeyChannelRef>& channels, double dtSec,
                                            float dValue);
// Sets one key channel's time and value exactly (numeric entry). Returns the key's new ref.
Result<KeyChannelRef> setKeyTimeValue(BlobTree& tree, const KeyChannelRef& k, double timeSec, float value);

// Interpolation of the segments starting at the keys.
Status setKeyInterp(BlobTree& tree, const std::vector<KeyRef>& keys, KeyInterp interp);
// Tangent mode: user (the stored d1 is used) or auto (Catmull-Rom). Switching
// to user stores the automatic slopes, so the curve does not change.
Status setKeyTangentMode(BlobTree& tree, const std::vector<KeyRef>& keys, bool user);
// Sets the slope (value per second) of one channel of a key (switching it to
// user tangents). Not available on rotations (they slerp).
Status setKeyTangent(BlobTree& tree, const KeyChannelRef& k, float slopePerSec);
// Slope of one channel at a key as the curve uses it (user or automatic).
float keySlope(const BlobTree& tree, const KeyChannelRef& k);

// Times (seconds) of every key of every animated track of node id (its own
// parameters only), sorted and unique. All nodes when id < 0.
std::vector<double> animatedKeyTimes(const BlobTree& tree, int id = -1);
// Last key time of any animated track (0 when nothing is animated).
double animationEndSec(const BlobTree& tree);

}  // namespace animorph
