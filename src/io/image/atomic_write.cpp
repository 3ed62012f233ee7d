// Temporary-file-and-rename writing (see atomic_write.h). POSIX: rename() within one directory is
// atomic, and fsync before it makes sure the renamed file's data has reached the disk.
#include "io/image/atomic_write.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace phos::io {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
    throw InputError("cannot write '" + path + "': " + reason);
}

// Creates a fresh, empty temporary file next to `path` and returns its name. O_EXCL guarantees
// we never write into someone else's file; pid + counter keeps concurrent writers apart.
std::string create_temp(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path target(path);
    const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
    for (int attempt = 0; attempt < 100; ++attempt) {
        const std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) +
                                 "-" + std::to_string(counter++);
        const std::string temp = (dir / name).string();
        // Mode 0666 filtered by the umask, the same permissions a plain fopen would give.
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return temp;
        }
        if (errno != EEXIST) fail(path, std::strerror(errno));
    }
    fail(path, "cannot create a temporary file");
}

// Flushes the file's data to disk; a rename of an unsynced file can survive a crash as an empty file.
void sync_file(const std::string& path, const std::string& temp) {
    const int fd = ::open(temp.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail(path, std::strerror(errno));
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0) fail(path, std::strerror(err));
}

}  // namespace

void atomic_write(const std::string& path, const std::function<void(const std::string&)>& write) {
    if (path.empty()) fail(path, "empty file name");
    const std::string temp = create_temp(path);
    try {
        write(temp);
        sync_file(path, temp);
        if (std::rename(temp.c_str(), path.c_str()) != 0) fail(path, std::strerror(errno));
    } catch (const std::exception& e) {
        std::remove(temp.c_str());
        // Keep an InputError that already names the target; wrap anything else.
        const std::string prefix = "cannot write '" + path + "'";
        const std::string what = e.what();
        if (what.rfind(prefix, 0) == 0) throw InputError(what);
        fail(path, what);
    } catch (...) {
        std::remove(temp.c_str());
        fail(path, "unknown error");
    }
}

}  // namespace phos::io
