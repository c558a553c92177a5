#pragma once
// A humanoid built like exported production rigs, to test stand-in fitting on
// what real files contain: an armature node with a 0.01 scale and a 90° turn
// (vertices and joints in its centimetre space), a scaled chest node, chains
// of helper bones without vertices (spine and arm twist bones, an IK pole
// target, end bones), a short neck, many small face bones and three-bone
// fingers. The body is one closed, welded surface (a union of capsules,
// polygonised); every vertex is skinned to its two nearest bones.
#include "core/rig/character.h"

namespace animorph {

struct RiggedFigureOptions {
  float height = 1.8f;        // world height of the figure (60: a file exported in other units)
  bool helperBones = true;    // spine / arm twist chains, IK pole target, end bones
  bool chestScale = true;     // the chest node carries a 1.5 scale, its children compensate
  int resolution = 160;       // polygonisation cells along the longest side
};

Character makeRiggedFigure(const RiggedFigureOptions& options = {});

}  // namespace animorph
