#pragma once
// The shapes of a glTF character actor that Convert to particles fills (docs/particles.md), posed
// at one clip time, in the actor's own space (the particle actor made from them takes the
// character's transform): its stand-in compiled as the morph compiles a posed stand-in
// (standin/standin.h standinProgram: convolution segments or capsules, f = sum - T), or its
// skinned meshes, skinned on the CPU as the viewport shows them, as one triangle mesh.
#include "core/rig/character.h"
#include "core/standin/standin.h"
#include "core/field/field_program.h"
#include "core/poly/mesh.h"

namespace animorph {

// The stand-in posed at clipTimeSec of clip (null: the rest pose).
FieldProgram posedStandinProgram(const Character& c, const Standin& standin, const AnimationClip* clip,
                                 float clipTimeSec);

// Every mesh of c posed at clipTimeSec of clip (null: the rest pose), concatenated over
// Character::meshNodes() (positions and triangles; no normals).
TriangleMesh posedCharacterMesh(const Character& c, const AnimationClip* clip, float clipTimeSec);

}  // namespace animorph
