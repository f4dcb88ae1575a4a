// The one way the tools write a file, as a database does: the bytes go to a temporary file in the target's
// folder, every write, the fsync and the close are checked, and only then is it renamed over the target. A
// failure (a full disk, no permission, a file size limit) removes the temporary file, leaves whatever had
// the target's name untouched, and throws with the path and the system's reason. Images of every format,
// reports, plots, view files and benchmark JSON all go through writeFileAtomically.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace ripple::apps {

// Writes `bytes` as the whole content of `file`. A symbolic link is followed: the file it names is
// replaced and the link stays. A target that exists and is not a regular file (a character device such as
// /dev/null, a pipe) is written in place, every write checked; a FIFO with no reader is refused rather than
// waited on. Throws std::runtime_error "FILE: cannot write <what>: No space left on device (ENOSPC)".
void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes, const std::string& what = "the file");

// Checks, before a long render, that `file` could be written: its folder takes a new file (made and removed
// again), or the existing non-regular target opens for writing. Nothing of the target's is touched. Throws
// std::runtime_error "FILE: cannot write <what> there: Permission denied (EACCES)".
void checkWritable(const std::filesystem::path& file, const std::string& what = "the file");

}  // namespace ripple::apps
