// The output directory and files written through a temporary name (issue 22: no output file
// left half-written, a clear error naming the path when the disk or the directory fails).
#pragma once

#include <filesystem>
#include <string_view>

namespace rf::output {

// Creates `directory` (and its parents) when missing and checks that a file can be written in
// it. Throws std::runtime_error naming the path and the reason (a file in its place, no
// permission, read-only or full file system).
void prepare_output_directory(const std::filesystem::path& directory);

// Writes `bytes` to `path` atomically: a temporary file next to it, flushed to the disk, then
// renamed over `path`. A reader, a crash or a full disk never leaves a partial `path`; on
// failure the temporary is removed and std::runtime_error names the path and the reason.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

// fsync of a finished file and of its directory entry (after a rename), so that a dump or
// run.json survives a power loss as well as a killed process. Errors are reported as
// std::runtime_error naming the path.
void sync_file(const std::filesystem::path& path);
void sync_directory_of(const std::filesystem::path& path);

}  // namespace rf::output
