#pragma once
// The frame loop of a bake (export/bake_route.h): every frame of a range baked on up to J threads,
// under a JobProgress (each frame advances it by one; its cancel flag is polled between frames).
#include <functional>

#include "core/util/job_progress.h"
#include "core/util/result.h"

namespace animorph {

// Runs bakeOne(k) for k = 0..count-1 on up to jobs threads (this one among them). A thread takes
// the next frame while no frame has failed and progress is not cancelled; before each frame the
// stage becomes "baking frame F (k+1 of N)", after each one progress advances by one and
// frameDone(F) runs (when set; on the baking thread). F = first + k.
// Returns: success; jobCancelled() when cancelled (or a frame returned it); else the error of the
// lowest failing frame as "frame F: <its error>".
Status runFrameLoop(int first, int count, int jobs, JobProgress& progress, const std::function<Status(int k)>& bakeOne,
                    const std::function<void(int frame)>& frameDone = {});

}  // namespace animorph
