#include "core/system/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "core/system/error.h"
#include "core/system/input_file.h"

namespace photon {
namespace {

std::string folderOf(const std::string& path) {
    std::size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) {
        return ".";
    }
    return slash == 0 ? "/" : path.substr(0, slash);
}

std::string nameOf(const std::string& path) {
    std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The file a write to `path` replaces: `path` itself, or what its chain of symbolic links ends in,
// so that a link keeps pointing where it did.
std::string finalTarget(const std::string& path) {
    std::string target = path;
    for (int hops = 0; hops < 16; ++hops) {
        struct stat info {};
        if (::lstat(target.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) {
            return target;
        }
        std::vector<char> link(PATH_MAX + 1, '\0');
        ssize_t n = ::readlink(target.c_str(), link.data(), PATH_MAX);
        if (n < 0) {
            return target;
        }
        std::string next(link.data(), std::size_t(n));
        target = next.front() == '/' ? next : folderOf(target) + "/" + next;
    }
    throw InputError(path + ": too many levels of symbolic links");
}

// Checks the target and its folder; returns the file to replace.
std::string checkedTarget(const std::string& path, const char* what) {
    if (path.empty()) {
        throw InputError(std::string("the ") + what + " path is empty");
    }
    std::string target = finalTarget(path);
    struct stat info {};
    if (::stat(target.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) {
        throw InputError(path + ": " + fileKind(info.st_mode) + ", not a file Photon can replace with the " + what);
    }
    std::string folder = folderOf(target);
    if (::stat(folder.c_str(), &info) != 0) {
        throw InputError(path + ": cannot write the " + what + ": folder " + folder + ": " + std::strerror(errno));
    }
    if (!S_ISDIR(info.st_mode)) {
        throw InputError(path + ": cannot write the " + what + ": " + folder + " is not a folder");
    }
    return target;
}

// The temporary files that exist now, for removePendingOutput() in a signal handler: a few slots
// of fixed buffers, each claimed and released through its lock-free state.
enum SlotState : int { kFree, kFilling, kPending, kRemoving };
struct PendingSlot {
    std::atomic<int> state{kFree};
    char path[PATH_MAX + 1] = {};
};
static_assert(std::atomic<int>::is_always_lock_free, "pending outputs are read in signal handlers");
PendingSlot gPending[4];

// The slot now holding `path`, or -1 if every slot is taken (the file is then not removed by a
// signal, but still never renamed over the target unless whole).
int registerPending(const std::string& path) {
    if (path.size() > PATH_MAX) {
        return -1;
    }
    for (int i = 0; i < 4; ++i) {
        int expected = kFree;
        if (gPending[i].state.compare_exchange_strong(expected, kFilling)) {
            std::memcpy(gPending[i].path, path.c_str(), path.size() + 1);
            gPending[i].state.store(kPending);
            return i;
        }
    }
    return -1;
}

void releasePending(int slot) {
    if (slot < 0) {
        return;
    }
    int expected = kPending;
    // Fails only while a signal handler removes the file, just before the process ends.
    gPending[slot].state.compare_exchange_strong(expected, kFree);
}

// A temporary file beside `target`, removed unless released.
struct Temporary {
    std::string path;
    int fd = -1;
    int slot = -1;

    explicit Temporary(const std::string& target) {
        std::string name = folderOf(target) + "/." + nameOf(target) + ".XXXXXX";
        std::vector<char> buffer(name.begin(), name.end());
        buffer.push_back('\0');
        fd = ::mkstemp(buffer.data());
        if (fd >= 0) {
            path = buffer.data();
            slot = registerPending(path);
        }
    }
    ~Temporary() {
        if (fd >= 0) {
            ::close(fd);
        }
        if (!path.empty()) {
            ::unlink(path.c_str());
        }
        releasePending(slot);
    }
};

}  // namespace

void removePendingOutput() {
    for (PendingSlot& slot : gPending) {
        int expected = kPending;
        if (slot.state.compare_exchange_strong(expected, kRemoving)) {
            ::unlink(slot.path);
        }
    }
}

void checkOutputPath(const std::string& path, const char* what) {
    std::string target = checkedTarget(path, what);
    Temporary probe(target);
    if (probe.fd < 0) {
        throw InputError(path + ": cannot write the " + what + " in " + folderOf(target) + ": " + std::strerror(errno));
    }
}

void writeOutputFile(const std::string& path, const std::string& bytes, const char* what) {
    std::string target = checkedTarget(path, what);
    Temporary file(target);
    auto fail = [&](const char* step) {
        throw RuntimeError(path + ": cannot write the " + what + " (" + step + "): " + std::strerror(errno));
    };
    if (file.fd < 0) {
        fail("create");
    }
    for (std::size_t done = 0; done < bytes.size();) {
        ssize_t n = ::write(file.fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            errno = n == 0 ? ENOSPC : errno;
            fail("write");
        }
        done += std::size_t(n);
    }
    // The permissions a newly created file would have (the temporary file is private).
    mode_t mask = ::umask(0);
    ::umask(mask);
    struct stat old {};
    mode_t mode = ::stat(target.c_str(), &old) == 0 ? (old.st_mode & 07777) : (0666 & ~mask);
    if (::fchmod(file.fd, mode) != 0) {
        fail("permissions");
    }
    if (::fsync(file.fd) != 0 && errno != EINVAL && errno != EROFS) {
        fail("flush");
    }
    int fd = file.fd;
    file.fd = -1;
    if (::close(fd) != 0) {
        fail("close");
    }
    if (::rename(file.path.c_str(), target.c_str()) != 0) {
        fail("rename");
    }
    file.path.clear();
}

}  // namespace photon
