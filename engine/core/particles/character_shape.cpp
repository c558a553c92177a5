#include "core/particles/character_shape.h"

#include "core/rig/pose.h"
#include "core/standin/character_pose.h"

namespace animorph {

FieldProgram posedStandinProgram(const Character& c, const Standin& standin, const AnimationClip* clip,
                                 float clipTimeSec) {
  const std::vector<PosedSegment> segs = poseStandin(standin, poseGlobals(c, clip, clipTimeSec), glm::mat4(1.0f));
  return standinProgram(standin.kind, standin.sharpness, segs);
}

TriangleMesh posedCharacterMesh(const Character& c, const AnimationClip* clip, float clipTimeSec) {
  CharacterPose pose = poseCharacter(c, clip, clipTimeSec, glm::mat4(1.0f));
  TriangleMesh m;
  for (size_t k = 0; k < pose.meshNodes.size(); ++k) {
    const Mesh& mesh = c.meshes[size_t(c.nodes[size_t(pose.meshNodes[k])].mesh)];
    for (uint32_t i : mesh.indices) m.indices.push_back(uint32_t(pose.firstVertex[k] + i));
  }
  m.positions = std::move(pose.positions);
  return m;
}

}  // namespace animorph
