// Writing a file all-or-nothing: into a temporary next to it, then renamed into place.
#pragma once

#include <filesystem>
#include <string>

namespace vitrum {

// Throws InputError naming the file when it cannot be written.
void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace vitrum
