#include "common/atomic_file.h"

#include <fstream>
#include <system_error>
#include <unistd.h>

#include "common/error.h"

namespace vitrum {

void writeFileAtomically(const std::filesystem::path& path, const std::string& contents) {
    std::filesystem::path temporary = path;
    temporary += ".tmp-" + std::to_string(::getpid());
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
