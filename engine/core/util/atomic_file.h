#pragma once
// Crash-safe file writes: write a temporary beside the target, fsync it,
// rename it over the target, fsync the directory. A failure at any step
// leaves the previous file untouched.
#include <cstddef>
#include <string>
#include <string_view>

#include "core/util/job_progress.h"
#include "core/util/result.h"

namespace animorph {

//
// The temporary is an unnamed O_TMPFILE where the file system allows (it gets
// a unique name ".NAME.tmpXXXXXXXXXXXXXXXX" only just before the rename),
// else a file created under such a name with O_EXCL, retried on collision.
// It is flock()ed while written; after a successful save, temporaries of the
// same target left by killed saves (unlocked) are removed.
Status writeFileAtomic(const std::string& path, std::string_view contents);

// Removes the unlocked temporaries ".NAME.tmp*" of target `path` left beside
// it by saves that were killed; returns how many were removed.
int removeStaleTemporaries(const std::string& path);

// Largest file readFile accepts unless told otherwise (projects, scenes,
// glTF files and their buffers).
inline constexpr size_t kMaxReadFileBytes = size_t(1) << 30;

// Whole file as a string; the error names the file as given and the reason.
// Only regular files of at most maxBytes are read: the file is opened without
// blocking and checked with fstat, so a directory, a FIFO or a device
// (/dev/zero) is refused at once instead of hanging or reading forever.
// With progress: read in 1 MiB pieces, each counted as done bytes (of the file's size, added to
// the total), cancel polled between them (then the error is jobCancelled()).
Result<std::string> readFile(const std::string& path, size_t maxBytes = kMaxReadFileBytes,
                             JobProgress* progress = nullptr);

}  // namespace animorph
