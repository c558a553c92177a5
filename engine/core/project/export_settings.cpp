#include "core/project/export_settings.h"

namespace animorph {

const char* exportFormatName(ExportFormat f) {
  switch (f) {
    case ExportFormat::GltfAnimated: return "gltf";
    case ExportFormat::PlySequence: return "ply";
    case ExportFormat::ObjSequence: return "obj";
    case ExportFormat::VdbSequence: return "vdb";
  }
  return "gltf";
}

bool exportFormatFromName(const std::string& name, ExportFormat& out) {
  for (int i = 0; i < kExportFormatCount; ++i)
    if (name == exportFormatName(ExportFormat(i))) {
      out = ExportFormat(i);
      return true;
    }
  return false;
}

const char* exportFormatLabel(ExportFormat f) {
  switch (f) {
    case ExportFormat::GltfAnimated: return "glTF animated (.glb)";
    case ExportFormat::PlySequence: return "PLY sequence (.ply per frame)";
    case ExportFormat::ObjSequence: return "OBJ sequence (.obj per frame)";
    case ExportFormat::VdbSequence: return "OpenVDB level sets (.vdb per frame)";
  }
  return "";
}

}  // namespace animorph
