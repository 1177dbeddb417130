#include "common/atomic_file.h"

#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "common/error.h"

namespace vitrum {

std::filesystem::path temporaryFor(const std::filesystem::path& path) {
    std::filesystem::path temporary = path;
    temporary += ".tmp-" + std::to_string(::getpid());
    return temporary;
}

void checkWritable(const std::filesystem::path& path) {
    // The temporary could be written, but renaming it onto a folder fails, after the work.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw inputError(path, 0, "cannot write the file: a folder has that name");
    const std::filesystem::path temporary = temporaryFor(path);
    errno = 0;
    if (!std::ofstream(temporary, std::ios::binary)) {
        const int reason = errno;
        throw inputError(
            path, 0, std::string("cannot write the file") + (reason ? ": " + std::string(std::strerror(reason)) : ""));
    }
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
}

void checkNotAnInput(const std::filesystem::path& output, const std::filesystem::path& input, const std::string& what) {
    std::error_code ec;
    if (std::filesystem::equivalent(output, input, ec))
        throw inputError(output, 0,
                         "cannot write the file: it is " + what + (output == input ? "" : " (" + input.string() + ")") +
                             ", which would be lost");
}

void writeFileAtomically(const std::filesystem::path& path, const std::string& contents) {
    const std::filesystem::path temporary = temporaryFor(path);
    {
        std::ofstream out(temporary, std::ios::binary);
        if (out) out.write(contents.data(), std::streamsize(contents.size()));
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw inputError(path, 0, "cannot write the file");
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw inputError(path, 0, "cannot write the file");
    }
}

}  // namespace vitrum
