#include "common/input_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"

namespace vitrum {
namespace {

std::string describeSize(std::uint64_t bytes) {
    if (bytes >= (std::uint64_t(1) << 30) && bytes % (std::uint64_t(1) << 30) == 0)
        return std::to_string(bytes >> 30) + " GiB";
    if (bytes + 1 >= (std::uint64_t(1) << 30)) return std::to_string((bytes + 1) >> 30) + " GiB";
    if (bytes >= (std::uint64_t(1) << 20)) return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

const char* kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a file";
}

[[noreturn]] void failToOpen(const std::filesystem::path& path, const std::string& what, int error) {
    if (error == ENOENT || error == ENOTDIR) throw inputError(path, 0, "cannot open " + what + " (no such file)");
    throw inputError(path, 0, "cannot open " + what + " (" + std::strerror(error) + ")");
}

void requireRegular(const std::filesystem::path& path, const std::string& what, const struct stat& status) {
    if (!S_ISREG(status.st_mode))
        throw inputError(path, 0, "cannot read " + what + ": not a regular file (" + kindOf(status.st_mode) + ")");
}

class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

}  // namespace

void requireRegularFile(const std::filesystem::path& path, const std::string& what) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) failToOpen(path, what, errno);
    requireRegular(path, what, status);
}

namespace {

// The bytes of the file into a vector or straight into a string (a text file's bytes were read
// into a vector, then copied into a string: twice a 100 MB OBJ's size at once).
template <class Bytes>
Bytes readBounded(const std::filesystem::path& path, const std::string& what, std::uint64_t maxBytes) {
    // O_NONBLOCK: opening a FIFO without a writer would wait for one; the check below refuses it.
    Descriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
    if (file.get() < 0) failToOpen(path, what, errno);
    struct stat status {};
    if (::fstat(file.get(), &status) != 0) failToOpen(path, what, errno);
    requireRegular(path, what, status);
    const std::string tooLarge = what + " is larger than " + describeSize(maxBytes) + ", the most vitrum reads";
    if (std::uint64_t(status.st_size) > maxBytes) throw inputError(path, 0, tooLarge);
    auto readSome = [&](void* into, std::size_t count) {
        for (;;) {
            const ssize_t n = ::read(file.get(), into, count);
            if (n >= 0) return std::size_t(n);
            if (errno != EINTR) throw inputError(path, 0, "cannot read " + what + " (" + std::strerror(errno) + ")");
        }
    };
    Bytes bytes(std::size_t(status.st_size), 0);
    std::size_t filled = 0;
    while (filled < bytes.size()) {
        const std::size_t n = readSome(bytes.data() + filled, bytes.size() - filled);
        if (n == 0) {
            bytes.resize(filled);  // it shrank while being read
            return bytes;
        }
        filled += n;
    }
    // A file that grew while being read (or that reports no size) is read on, to the limit.
    char chunk[1 << 16];
    while (const std::size_t n = readSome(chunk, sizeof(chunk))) {
        if (bytes.size() + n > maxBytes) throw inputError(path, 0, tooLarge);
        bytes.insert(bytes.end(), chunk, chunk + n);
    }
    return bytes;
}

}  // namespace

std::vector<unsigned char> readInputFile(const std::filesystem::path& path, const std::string& what,
                                         std::uint64_t maxBytes) {
    return readBounded<std::vector<unsigned char>>(path, what, maxBytes);
}

std::string readInputText(const std::filesystem::path& path, const std::string& what, std::uint64_t maxBytes) {
    return readBounded<std::string>(path, what, maxBytes);
}

std::string readInputLines(const std::filesystem::path& path, const std::string& what, std::uint64_t maxBytes) {
    std::string text = readInputText(path, what, maxBytes);
    if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
    const bool wide = text.rfind("\xFF\xFE", 0) == 0 || text.rfind("\xFE\xFF", 0) == 0 ||
                      text.rfind(std::string("\0\0\xFE\xFF", 4), 0) == 0;
    if (wide) throw inputError(path, 0, "cannot read " + what + ": it is UTF-16 or UTF-32 text; vitrum reads ASCII and UTF-8");
    if (text.find('\r') != std::string::npos) {
        std::size_t kept = 0;
        for (std::size_t i = 0; i < text.size(); ++i) {
            if (text[i] != '\r') {
                text[kept++] = text[i];
            } else if (i + 1 == text.size() || text[i + 1] != '\n') {
                text[kept++] = '\n';
            }
        }
        text.resize(kept);
    }
    if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
        const int line = 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'));
        throw inputError(path, line, "cannot read " + what + ": a NUL byte; vitrum reads ASCII and UTF-8 text");
    }
    return text;
}

}  // namespace vitrum
