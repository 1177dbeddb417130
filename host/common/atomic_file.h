// Writing a file all-or-nothing: into a temporary next to it, then renamed into place.
#pragma once

#include <filesystem>
#include <string>

namespace vitrum {

// The temporary a file is written to before it is renamed to `path`: next to it, named for this
// process, so two processes writing one output never share it.
std::filesystem::path temporaryFor(const std::filesystem::path& path);

// Throws InputError naming the file when it cannot be written.
void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

// Throws InputError naming the file, with the system's reason, when no file can be created at
// `path` (a name too long, a read-only folder, a folder of that name): the temporary that
// writeFileAtomically and writeImage would write is created and removed. For outputs, before any
// long work.
void checkWritable(const std::filesystem::path& path);

// Throws InputError naming `output` when it is `input` (the same file, by any path or link), which
// writing the output would destroy; `what` says what the input is ("the scene file").
void checkNotAnInput(const std::filesystem::path& output, const std::filesystem::path& input, const std::string& what);

}  // namespace vitrum
