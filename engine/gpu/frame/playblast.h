#pragma once
// Playblasts: baked meshes drawn offscreen (frame/mesh_sequence_renderer.h, a Vulkan context of
// its own) with the viewport's camera or one camera framing every frame, piped into an .mp4 by ffmpeg (export/mp4_writer.h).
// Used by animorph-cli bake --mp4 / farm assemble --mp4 and, as the editor's PlayblastRunner
// (export/playblast_job.h), by File > Export > Playblast..., on the job's thread.
#include <optional>
#include <vector>

#include "core/export/playblast_job.h"
#include "core/export/mp4_writer.h"
#include "core/poly/mesh.h"

namespace animorph::gpu {

// meshes[k] is frame o.firstFrame + k, seen by camera (none: one camera framing every frame).
// progress (may be null): counts seconds from what it had done (the total is the rate so far
// times the frames), so its time left follows the drawing; its cancel is polled between frames
// (then jobCancelled(), no file left).
Result<PlayblastReport> playblastMeshes(const std::vector<TriangleMesh>& meshes, const ViewOptions& view,
                                        const Mp4Options& o, const std::optional<OrbitCamera>& camera,
                                        JobProgress* progress);

// The editor's playblast of project: the frames baked at s.resolution, then drawn at
// s.width x s.height (burn-in of the frame number and stage when s.burnIn) into s.output
// (relative to baseDir), seen by camera when s.viewportCamera and a camera is given (else one
// camera framing every frame). Errors name the frame or the file and the reason.
Result<PlayblastReport> playblastProject(const Project& project, const std::string& baseDir,
                                         const PlayblastSettings& s, const std::optional<OrbitCamera>& camera,
                                         JobProgress& progress);

}  // namespace animorph::gpu
