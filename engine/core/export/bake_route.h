#pragma once
// The one route every bake of a project takes: animorph-cli bake (and the farm's chunks, which
// run it), File > Export... (export/export_project.h) and the playblast's frames
// (gpu/frame/playblast.h). A fix to the frame loop, the outputs, the coherence or the report
// reaches all of them.
//
// The frames come from a ProjectFrames (a morph or an animorphosis, prepared once); they are baked
// as BakeSettings say (frames, resolution, threads, coherence, outputs, a plugged-in polygoniser
// for the morph's B->C stage) under a JobProgress (each frame advances it by one; the caller sets
// the total; cancel is polled between frames and inside the polygonisation), and the outputs are
// written staged: a failed or cancelled bake leaves no file of its own behind (bake_sink.h).
#include "core/export/bake_report.h"
#include "core/export/bake_settings.h"
#include "core/export/project_frames.h"
#include "core/util/job_progress.h"
#include "core/util/result.h"

namespace animorph {

// Runs the bake. Errors name the frame ("frame 12: ...") or the file and the reason; bad settings
// (a range, resolution, jobs or coherence out of range, a PLY / OBJ sequence without a folder)
// are named before anything is baked; a cancelled bake returns jobCancelled().
Result<BakeReport> bakeProject(const ProjectFrames& frames, const BakeSettings& s, JobProgress& progress);

// The settings' problem ("" when none), as bakeProject names it.
std::string bakeSettingsProblem(const BakeSettings& s);

}  // namespace animorph
