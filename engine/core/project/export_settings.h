#pragma once
// The last settings of File > Export... (saved in the project, changed through a command like any
// other project setting): what to write, which frames, at which resolution, and where.
#include <string>

namespace animorph {

enum class ExportFormat {
  GltfAnimated,  // one animated .glb of the whole range (io/gltf_sequence_export.h)
  PlySequence,   // DIR/NAME_####.ply
  ObjSequence,   // DIR/NAME_####.obj
  VdbSequence,   // DIR/NAME_####.vdb: OpenVDB level sets of the implicit frames (io/vdb_export.h)
};

// "gltf", "ply", "obj", "vdb" (the project file's names); fromName: false on an unknown name.
const char* exportFormatName(ExportFormat f);
bool exportFormatFromName(const std::string& name, ExportFormat& out);
// "glTF animated (.glb)", ... as the dialog lists them.
const char* exportFormatLabel(ExportFormat f);
inline constexpr int kExportFormatCount = 4;

struct ExportSettings {
  ExportFormat format = ExportFormat::GltfAnimated;
  // Frames first..last (inclusive). useTimeline: the timeline's range instead (the default).
  bool useTimeline = true;
  int first = 0, last = 96;
  int resolution = 64;  // polygonisation cells along the longest side (2..1024)
  // The .glb file (GltfAnimated) or the folder of the sequence; empty: not chosen yet.
  std::string output;
  bool operator==(const ExportSettings&) const = default;
};

}  // namespace animorph
