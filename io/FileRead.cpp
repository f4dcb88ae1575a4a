// Regular files only, read whole within a limit (see FileRead.h).
#include "io/FileRead.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace ripple::apps {

const char* fileKindName(unsigned mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a plain file";
}

std::string tooLargeReason(uint64_t size, uint64_t maxBytes) {
    return std::to_string(size) + " bytes is larger than the limit of " + std::to_string(maxBytes);
}

FileDescriptor::~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
}

FileDescriptor& FileDescriptor::operator=(FileDescriptor&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = other.release();
    }
    return *this;
}

FileDescriptor openRegularFile(const std::filesystem::path& file, bool noFollow, uint64_t& size, std::string& error) {
    // O_NONBLOCK: opening a FIFO with no writer would otherwise wait forever; it changes nothing for regular files.
    FileDescriptor fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY | (noFollow ? O_NOFOLLOW : 0)));
    if (fd.get() < 0) {
        const int e = errno;
        if (e == ENOENT) error = "no such file";
        else if (e == ELOOP && noFollow) error = "is a symbolic link (it changed after it was checked)";
        else error = std::string("cannot open it: ") + std::strerror(e);
        return FileDescriptor();
    }
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0) {
        error = std::string("cannot stat it: ") + std::strerror(errno);
        return FileDescriptor();
    }
    if (!S_ISREG(st.st_mode)) {
        error = std::string("is not a regular file (") + fileKindName(st.st_mode) + ")";
        return FileDescriptor();
    }
    size = uint64_t(st.st_size);
    return fd;
}

template <typename Bytes>
bool readRegularFile(const std::filesystem::path& file, uint64_t maxBytes, bool noFollow, Bytes& out,
                     std::string& error) {
    uint64_t size = 0;
    const FileDescriptor fd = openRegularFile(file, noFollow, size, error);
    if (fd.get() < 0) return false;
    if (size > maxBytes) {
        error = tooLargeReason(size, maxBytes);
        return false;
    }
    out.resize(size_t(size));
    size_t got = 0;
    while (got < size) {
        const ssize_t n = ::read(fd.get(), out.data() + got, size_t(size) - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            error = std::string("read failed: ") + std::strerror(errno);
            return false;
        }
        if (n == 0) {
            error = "read failed: the file shrank while it was read";
            return false;
        }
        got += size_t(n);
    }
    return true;
}

template bool readRegularFile(const std::filesystem::path&, uint64_t, bool, std::string&, std::string&);
template bool readRegularFile(const std::filesystem::path&, uint64_t, bool, std::vector<unsigned char>&, std::string&);

std::string readRegularFile(const std::filesystem::path& file, uint64_t maxBytes, const std::string& what) {
    std::string bytes, error;
    if (!readRegularFile(file, maxBytes, false, bytes, error))
        throw std::runtime_error(file.string() + ": " + (what.empty() ? "" : what + ": ") + error);
    return bytes;
}

bool pathInside(const std::filesystem::path& root, const std::filesystem::path& p) {
    auto r = root.begin(), q = p.begin();
    for (; r != root.end(); ++r, ++q)
        if (q == p.end() || *r != *q) return false;
    return true;
}

std::filesystem::path resolveBeside(const std::filesystem::path& header, const std::string& relative, std::string& error) {
    const std::filesystem::path named(relative);
    if (named.is_absolute()) {
        error = "is an absolute path; give one relative to the header's folder";
        return {};
    }
    std::error_code ec;
    const std::filesystem::path folder = std::filesystem::weakly_canonical(std::filesystem::absolute(header).parent_path(), ec);
    if (ec) {
        error = "cannot be resolved: " + ec.message();
        return {};
    }
    std::filesystem::path resolved = std::filesystem::weakly_canonical(folder / named, ec);
    if (ec || !pathInside(folder, resolved)) {
        error = "resolves outside the header's folder " + folder.string();
        return {};
    }
    return resolved;
}

}  // namespace ripple::apps
