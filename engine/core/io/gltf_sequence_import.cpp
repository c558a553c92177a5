#include "core/io/gltf_sequence_import.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>

#include "core/io/gltf_import.h"

namespace animorph {

namespace {

// The frame number of a node named NAME_<digits> (at most 9 digits), or -1.
int frameOfNode(const std::string& node, const std::string& name) {
  if (node.size() <= name.size() + 1 || node.compare(0, name.size(), name) != 0 || node[name.size()] != '_') return -1;
  const std::string digits = node.substr(name.size() + 1);
  if (digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(uint8_t(c)); }))
    return -1;
  return std::atoi(digits.c_str());
}

}  // namespace

Result<std::vector<SequenceFrame>> readGltfSequence(const std::string& path, const std::string& name) {
  auto ch = importGltf(path);
  if (!ch) return Error{ch.error()};
  std::vector<SequenceFrame> frames;
  for (const Node& n : ch->nodes) {
    const int f = frameOfNode(n.name, name);
    if (f < 0) continue;
    SequenceFrame fr;
    fr.frame = f;
    if (n.mesh >= 0) {
      const Mesh& m = ch->meshes[size_t(n.mesh)];
      fr.mesh.positions = m.positions;
      fr.mesh.normals = m.normals;
      fr.mesh.indices = m.indices;
      fr.mesh.colors = m.colors;
    }
    frames.push_back(std::move(fr));
  }
  if (frames.empty()) return Error{path + ": no frame node named " + name + "_#### (not a sequence baked under this name)"};
  std::sort(frames.begin(), frames.end(), [](const SequenceFrame& a, const SequenceFrame& b) { return a.frame < b.frame; });
  for (size_t i = 1; i < frames.size(); ++i)
    if (frames[i].frame == frames[i - 1].frame)
      return Error{path + ": frame " + std::to_string(frames[i].frame) + " has two nodes named " + name + "_####"};
  return frames;
}

}  // namespace animorph
