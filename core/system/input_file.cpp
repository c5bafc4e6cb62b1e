#include "core/system/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/loaders/json_node.h"
#include "core/system/error.h"

namespace photon {
namespace {

std::string mib(std::uint64_t bytes) { return formatNumber(double(bytes) / double(1 << 20)) + " MiB"; }

// "a scene file", "an environment map", "an OBJ file": the article by the first letter.
std::string withArticle(const char* what) {
    bool vowel = what[0] != '\0' && std::strchr("AEIOUaeiou", what[0]) != nullptr;
    return (vowel ? "an " : "a ") + std::string(what);
}

// Closes the descriptor on every way out.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) {
            ::close(fd);
        }
    }
};

}  // namespace

const char* fileKind(unsigned mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string readInputFile(const std::string& path, std::uint64_t limit, const char* what) {
    if (path.empty()) {
        throw InputError(std::string("the ") + what + " path is empty");
    }
    // O_NONBLOCK: opening a FIFO does not wait for a writer; it is refused below, like any other
    // file that is not regular.
    Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)};
    if (file.fd < 0) {
        throw InputError(path + ": cannot open " + what + ": " + std::strerror(errno));
    }
    struct stat info {};
    if (::fstat(file.fd, &info) != 0) {
        throw InputError(path + ": cannot read " + what + ": " + std::strerror(errno));
    }
    if (!S_ISREG(info.st_mode)) {
        throw InputError(path + ": " + fileKind(info.st_mode) + ", not " + withArticle(what));
    }
    if (std::uint64_t(info.st_size) > limit) {
        throw InputError(path + ": " + what + " of " + mib(std::uint64_t(info.st_size)) + ", larger than the " +
                         mib(limit) + " Photon reads");
    }
    std::string text(std::size_t(info.st_size), '\0');
    std::size_t done = 0;
    // Read up to the size fstat gave and one byte more, to notice a file that grows while it is read.
    for (;;) {
        if (done == text.size()) {
            if (text.size() >= limit + 1) {
                break;
            }
            text.resize(std::min<std::uint64_t>(text.size() * 2 + 4096, limit + 1));
        }
        ssize_t n = ::read(file.fd, &text[done], text.size() - done);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0) {
            throw InputError(path + ": cannot read " + what + ": " + std::strerror(errno));
        }
        if (n == 0) {
            break;
        }
        done += std::size_t(n);
    }
    if (done > limit) {
        throw InputError(path + ": " + what + " larger than the " + mib(limit) + " Photon reads");
    }
    text.resize(done);
    return text;
}

}  // namespace photon
