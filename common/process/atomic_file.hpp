// Replaces a file's content all at once: the new bytes go to a temporary file
// beside it, are flushed to the disk, and renamed over the old file, so a
// crash or power cut leaves either the old or the new content, never a part.
#pragma once

#include <string>

namespace slamer {

// Throws std::runtime_error (one line, naming the file and the reason).
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace slamer
