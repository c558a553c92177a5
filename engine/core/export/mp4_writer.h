#pragma once
// An H.264 .mp4 written by ffmpeg (Debian package ffmpeg) from raw RGBA frames piped to it: the
// playblast of animorph-cli bake --mp4, farm assemble --mp4 and the editor's File > Export >
// Playblast.... The file is written under a temporary name (PATH.part-PID) and renamed to PATH by
// finish() once ffmpeg succeeded; a writer destroyed before that (cancelled, failed) stops ffmpeg
// and removes the temporary: no half-written file is left.
//
// Burn-in: the frame number (4 digits) and the stage label of its span (export/frame_stage.h) in
// the top-left corner, white on a half-transparent box, drawn by ffmpeg's drawtext with DejaVu
// Sans Mono (fonts-dejavu-core).
#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/export/frame_stage.h"
#include "core/util/result.h"

namespace animorph {

struct Mp4Options {
  std::string path;  // the .mp4 (its folder must exist)
  uint32_t width = 1280, height = 720;  // even
  double fps = 24.0;
  bool burnIn = false;
  int firstFrame = 0;                    // the burnt-in number of the first frame
  std::vector<FrameStageSpan> stages;    // burnt in after the number; empty: the number alone
};

// The ffmpeg filter that draws the burn-in ("" without burnIn); one drawtext per stage span,
// enabled on its frames.
std::string mp4BurnInFilter(const Mp4Options& o);

class Mp4Writer {
 public:
  // Starts ffmpeg. Errors: a size that is odd or below 16, ffmpeg not found, the font missing.
  static Result<std::unique_ptr<Mp4Writer>> start(const Mp4Options& o);
  ~Mp4Writer();
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  // One frame of width * height RGBA pixels, top row first. Errors name the file and what ffmpeg said.
  Status addFrame(const std::vector<uint8_t>& rgba);
  // Ends the input, waits for ffmpeg and renames the temporary to the path.
  Status finish();
  int frames() const { return frames_; }

 private:
  Mp4Writer() = default;
  std::string ffmpegSaid() const;  // the last line ffmpeg wrote to its log
  void stop();                     // ffmpeg ended (killed when still running), temporaries removed
  Mp4Options o_;
  std::string tmp_, log_;
  pid_t pid_ = -1;
  int fd_ = -1;
  int frames_ = 0;
  bool finished_ = false;
};

}  // namespace animorph
