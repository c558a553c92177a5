#pragma once
// What one bake of a project's frames does (export/bake_route.h): which frames, how fine, on how
// many threads, with which temporal coherence, into which outputs, with which polygoniser for the
// morph's implicit stage. animorph-cli bake fills it from its arguments, File > Export... from the
// project's ExportSettings, the playblast from its PlayblastSettings.
#include <functional>
#include <string>

#include "core/export/project_frames.h"

namespace animorph {

// Where the frames go. Every file is written under a temporary name and renamed into place when
// every frame is done (export/frame_files.h, StagedFiles): a failed or cancelled bake leaves what
// was at the outputs before.
struct BakeOutputs {
  std::string prefix = "frame";  // NAME in NAME_####.EXT, and the glTF's root and animation name
  std::string dir;               // the folder of the PLY / OBJ frames (needed with ply or obj)
  bool ply = false;              // DIR/NAME_####.ply, binary PLY
  bool obj = false;              // DIR/NAME_####.obj, Wavefront OBJ
  std::string gltf;              // one animated .glb of the range (io/gltf_sequence_export.h); "": none
  std::string vdbDir;            // VDB/NAME_####.vdb level sets of the frames with a field; "": none.
                                 // A range without any such frame is an error (nothing to write).
  bool keepMeshes = false;       // every frame's mesh handed back in the report (--png, --mp4, playblast)
};

struct BakeSettings {
  int first = 0, last = 0;  // scene frames, inclusive; 0 <= first <= last
  int resolution = 48;      // polygonisation cells along the longest side, 2..1024
  // Frames baked in parallel (1..256); the files are the same for any number. Each frame's
  // polygoniser then runs on one thread (jobs > 1) or on all (jobs 1).
  int jobs = 1;
  // An animorphosis: above 0, its frames are polygonised in order on one grid with temporal
  // coherence (poly/frame_sequence.h; jobs is then not used), each vertex within this many cells
  // of a full polygonisation's; 0: every frame on its own grid. 0..0.5. A morph ignores it.
  float coherence = 0.0f;
  BakeOutputs outputs;
  // A morph's collapse and expansion frames are two closed shells, the transitioned mesh and the
  // stand-in core inside it: by default a frame is written as what is seen, the boundary of their
  // union (scene/visible_surface.h); true keeps both shells (animorph-cli bake --keep-inner-shell).
  bool keepInnerShell = false;
  // An animorphosis' frames carry the primitives' colours as vertex colours (field/surface_color.h);
  // false: none (animorph-cli bake --no-color), which saves the colour pass (docs/export.md).
  bool colors = true;
  // A morph: measure every frame for the continuity report (export/bake_continuity.h): its volume,
  // and the continuity ratio over the range's part of A..D. Needs the meshes, so it costs a mesh
  // per frame even when only volumes are written.
  bool measureContinuity = false;
  // A morph's B->C frames on another polygoniser (project_frames.h); empty: the CPU's.
  ImplicitStagePolygonizer implicitStage;
  // Called after each frame is baked (from the worker thread that baked it), e.g. a progress bar.
  std::function<void(int frame)> frameDone;
};

}  // namespace animorph
