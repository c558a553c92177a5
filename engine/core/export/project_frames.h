#pragma once
// The frames a project bakes into: its morph (prepared once: characters loaded, vertices bound)
// or, when it has only an animorphosis, its C(t). The source of every bake (export/bake_route.h:
// animorph-cli bake, File > Export..., the playblast, the farm's chunks); thread-safe to read from
// several worker threads at once.
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/animorphosis/animorphosis_timing.h"
#include "core/animorphosis/generic_tree.h"
#include "core/export/frame_volume.h"
#include "core/project/project.h"
#include "core/scene/morph_runtime.h"
#include "core/poly/mesh.h"
#include "core/standin_morph/morph_continuity.h"
#include "core/util/result.h"

namespace animorph {

class SharedGenericCompiler;  // scene/animorphosis_preview_source.h

// A polygoniser for the morph's implicit stage (B->C) plugged in by the caller (animorph-cli bake
// --gpu: the GPU's), so that the core needs no GPU: the frame at timeSec on the same field and grid
// as the CPU's (morphImplicitField), its mesh in world space. Called from the bake's worker
// threads, possibly several at once: a polygoniser that is one device serialises inside. Its error
// fails the frame (no fallback to the CPU).
using ImplicitStagePolygonizer =
    std::function<Result<MorphFrame>(const MorphRuntime& rt, double timeSec, int resolution)>;

// One baked frame: its mesh and, for a morph, its stage and stand-in core.
struct BakedFrame {
  // World space (a morph), the trees' own space (an animorphosis). A collapse or expansion frame
  // is its visible surface (scene/visible_surface.h), or with FrameBakeSettings::keepInnerShell
  // both closed shells, the stand-in core the last coreTriangles triangles.
  TriangleMesh mesh;
  MorphStage stage = MorphStage::Morph;  // an animorphosis' frames count as Morph
  size_t coreTriangles = 0;  // the stand-in core's triangles in the evaluated frame (0: it has none)
  // With FrameBakeSettings::measure, a morph's frame: the evaluated frame's measure (its volume the
  // union of both shells', standin_morph/morph_continuity.h), and its visible surface where mesh
  // is not it (keepInnerShell and a core).
  FrameMeasure measure;
  std::optional<TriangleMesh> visible;
  const TriangleMesh& visibleMesh() const { return visible ? *visible : mesh; }
};

// How one frame is baked.
struct FrameBakeSettings {
  int resolution = 48;  // polygonisation cells along the longest side
  int threads = 0;      // polygoniser threads; 0: all
  const std::atomic<bool>* cancel = nullptr;  // polled inside the polygonisation; may be null
  ImplicitStagePolygonizer implicitStage;      // a morph's B->C frames; empty: the CPU's
  // A collapse or expansion frame is two closed shells, the transitioned mesh and the stand-in
  // core inside it: false writes what is seen (the boundary of their union), true keeps both.
  bool keepInnerShell = false;
  bool colors = true;    // an animorphosis' frames: vertex colours (BakeSettings::colors)
  bool measure = false;  // fill BakedFrame::measure and ::visible (the bake's continuity report)
};

class ProjectFrames {
 public:
  // Errors name the project element and the reason ("export: ..." is the caller's prefix); a
  // project with neither a morph nor an animorphosis is an error too.
  static Result<ProjectFrames> prepare(const Project& p, const std::string& baseDir);

  // What the user should know about the prepared morph (prepareMorph's notes); none for an
  // animorphosis.
  const std::vector<std::string>& notes() const;
  // The prepared morph; null when the project bakes an animorphosis.
  const MorphRuntime* morph() const { return morph_.get(); }
  // The animorphosis' in-between tree C; null when the project bakes a morph.
  const GenericTree* animorphosis() const { return generic_.get(); }
  const Timeline& timeline() const { return timeline_; }

  // Scene frame f baked as s says (a collapse or expansion frame as its visible surface unless
  // s.keepInnerShell). A cancel seen during the polygonisation comes back as
  // jobCancelled() (util/job_progress.h); other errors name the reason (not the frame).
  Result<BakedFrame> frame(int frame, const FrameBakeSettings& s) const;
  // The stage of frame f without baking it (an animorphosis: Morph).
  MorphStage stageAt(int frame) const;
  // Frame f's implicit field as a level set; none for a skinned-mesh frame of a morph.
  // threads: 0 = all. colors: the surface colour beside it (LevelSetSettings::colors).
  FrameLevelSet levelSet(int frame, int resolution, const std::atomic<bool>* cancel, int threads = 0,
                         bool colors = false) const;
  // An animorphosis' C at frame f as one program (for a sequence on one grid); needs animorphosis().
  // Compiled straight from C (animorphosis/compile_generic.h): compileGeneric's program, field for
  // field, without the BlobTree snapshot (one compile at a time: the compiler keeps a frame's values).
  FieldProgram animorphosisProgram(int frame) const;

 private:
  Timeline timeline_;
  std::shared_ptr<const MorphRuntime> morph_;  // or else the animorphosis:
  std::shared_ptr<const GenericTree> generic_;
  std::shared_ptr<SharedGenericCompiler> compiler_;  // C compiled directly (shared by copies, serialised)
  AnimorphosisTiming timing_;
};

}  // namespace animorph
