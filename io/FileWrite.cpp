// Atomic replacement of the tools' output files (see FileWrite.h).
#include "io/FileWrite.h"

#include "io/FileRead.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace ripple::apps {

namespace {

// "No space left on device (ENOSPC)".
std::string reason(int error) {
    const char* name = strerrorname_np(error);
    return std::string(std::strerror(error)) + (name ? std::string(" (") + name + ")" : std::string());
}

// "FILE: cannot write the image: No space left on device (ENOSPC)".
[[noreturn]] void fail(const std::filesystem::path& file, const std::string& action, int error) {
    throw std::runtime_error(file.string() + ": " + action + ": " + reason(error));
}

// The file a write to `file` reaches: symbolic links followed, so that a link keeps pointing where it did.
std::filesystem::path writeTarget(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(file, ec)) return file;
    const std::filesystem::path target = std::filesystem::weakly_canonical(file, ec);
    return ec ? file : target;
}

// Writes all of `bytes` to `fd`; returns 0 or the errno of the failed write.
int writeAll(int fd, std::string_view bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return errno;
        if (n == 0) return EIO;
        done += size_t(n);
    }
    return 0;
}

// Opens an existing target that is not a regular file (a device, a pipe) for writing in place; a FIFO
// with no reader fails with ENXIO instead of waiting for one.
FileDescriptor openInPlace(const std::filesystem::path& target, const std::filesystem::path& file,
                           const std::string& action) {
    FileDescriptor fd(::open(target.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) {
        if (errno == ENXIO) throw std::runtime_error(file.string() + ": " + action + ": a FIFO with no reader");
        fail(file, action, errno);
    }
    const int flags = ::fcntl(fd.get(), F_GETFL);
    if (flags >= 0) ::fcntl(fd.get(), F_SETFL, flags & ~O_NONBLOCK);
    return fd;
}

// The state of an existing target: absent, a regular file (its mode kept by the replacement), or another kind.
struct Existing {
    bool exists = false, regular = false;
    mode_t mode = 0;
};

Existing existing(const std::filesystem::path& target, const std::filesystem::path& file, const std::string& action) {
    struct stat st {};
    if (::stat(target.c_str(), &st) != 0) {
        if (errno == ENOENT) return {};
        fail(file, action, errno);
    }
    if (S_ISDIR(st.st_mode)) fail(file, action, EISDIR);
    return {true, bool(S_ISREG(st.st_mode)), st.st_mode & 07777};
}

// A new temporary file beside `target`, named after it so that a leftover one (after a crash) says whose it was.
FileDescriptor makeTemporary(const std::filesystem::path& target, const std::filesystem::path& file,
                             const std::string& action, std::string& temporaryName) {
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
    std::string name = ".";  // (a "." + string temporary trips GCC 12's -Wrestrict, a false positive)
    name += target.filename().string();
    name += ".partial-XXXXXX";
    temporaryName = (folder / name).string();
    FileDescriptor fd(::mkostemp(temporaryName.data(), O_CLOEXEC));
    if (fd.get() < 0) fail(file, action, errno);
    return fd;
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes, const std::string& what) {
    const std::string action = "cannot write " + what;
    const std::filesystem::path target = writeTarget(file);
    const Existing before = existing(target, file, action);
    if (before.exists && !before.regular) {
        FileDescriptor fd = openInPlace(target, file, action);
        if (const int error = writeAll(fd.get(), bytes)) fail(file, action, error);
        if (::close(fd.release()) != 0) fail(file, action, errno);
        return;
    }
    std::string temporary;
    FileDescriptor fd = makeTemporary(target, file, action, temporary);
    // mkostemp makes the file 0600; the replacement takes the target's mode, or what a new file would get.
    mode_t mode = before.mode;
    if (!before.exists) {
        const mode_t mask = ::umask(0);
        ::umask(mask);
        mode = 0666 & ~mask;
    }
    int error = ::fchmod(fd.get(), mode) != 0 ? errno : 0;
    if (!error) error = writeAll(fd.get(), bytes);
    if (!error && ::fsync(fd.get()) != 0) error = errno;
    if (!error && ::close(fd.release()) != 0) error = errno;
    if (!error && ::rename(temporary.c_str(), target.c_str()) != 0) error = errno;
    if (error) {
        ::unlink(temporary.c_str());
        fail(file, action, error);
    }
    // The rename is durable once the folder is synced; a failure here loses nothing already written.
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
    const FileDescriptor dir(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dir.get() >= 0) ::fsync(dir.get());
}

void checkWritable(const std::filesystem::path& file, const std::string& what) {
    const std::string action = "cannot write " + what + " there";
    const std::filesystem::path target = writeTarget(file);
    if (const Existing before = existing(target, file, action); before.exists && !before.regular) {
        openInPlace(target, file, action);
        return;
    }
    std::string temporary;
    const FileDescriptor fd = makeTemporary(target, file, action, temporary);
    ::unlink(temporary.c_str());
}

}  // namespace ripple::apps
