#pragma once
// What the timeline and the camera need to know about the selection:
// key frames of its animation and its bounds in the scene.
#include <optional>
#include <vector>

#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "core/math/bounds.h"

namespace animorph {

// The character of an actor from the cache (null when missing or failed to load).
const Character* actorCharacter(const Document& doc, AssetCache& assets, const Actor& actor);

// Timeline frames (sorted, unique, inside the range) that hold a key of the
// selected actor's clip: the clip's key times mapped through the actor's
// time offset and speed (t = offset + clipTime / speed), repeated per clip
// cycle when the actor loops. When a node is selected only the channels of
// that node count. Empty without a selection or a loaded clip. For a
// BlobTree actor: the key times of its animated parameters (the selected
// node's own, or every node's), mapped the same way.
std::vector<int> selectionKeyFrames(const Document& doc, AssetCache& assets);

// World-space bounds of the selection at timeSec (skinned pose): the selected
// actor's meshes, or a selected node's position with a margin; without a
// selection, every visible actor. BlobTree actors: the bounds of their field
// (tightened), or of a selected node's skeleton. Empty bounds when nothing is loaded.
Bounds selectionBounds(const Document& doc, AssetCache& assets, double timeSec);

}  // namespace animorph
