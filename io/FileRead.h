// The one way the tools open a file to read: regular files only, refused from fstat of the opened file
// without blocking on a FIFO or reading a byte of a device, and read whole up to a size limit suited to the
// file's kind. Every reader (glTF and its buffers and images, volumes, environment and reference images,
// view files) goes through here, so /dev/zero, a FIFO or a directory is refused at once, by name.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace ripple::apps {

// Size limits by kind of file: large enough for any real file of the kind, small enough that a wrong path
// fails before memory does.
inline constexpr uint64_t kMaxImageFileBytes = uint64_t(1) << 31;   // stb and tinyexr index bytes by int
inline constexpr uint64_t kMaxViewFileBytes = uint64_t(1) << 20;    // a view file is a few kilobytes

// An open file descriptor, closed when it goes.
class FileDescriptor {
public:
    explicit FileDescriptor(int fd = -1) : fd_(fd) {}
    ~FileDescriptor();
    FileDescriptor(FileDescriptor&& other) noexcept : fd_(other.release()) {}
    FileDescriptor& operator=(FileDescriptor&& other) noexcept;
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }
    int release() {
        const int fd = fd_;
        fd_ = -1;
        return fd;
    }

private:
    int fd_;
};

// Opens `file` for reading when it is a regular file: FIFOs, devices, directories and sockets are refused
// without waiting on them. noFollow: a symbolic link as the last component is refused too. On failure
// returns an invalid descriptor and sets `error` ("is not a regular file (a FIFO)"); `size` is the file's.
FileDescriptor openRegularFile(const std::filesystem::path& file, bool noFollow, uint64_t& size, std::string& error);

// Reads `file` whole into `out` when it is a regular file of at most maxBytes (see openRegularFile). On
// failure returns false and sets `error`, without the file's name.
template <typename Bytes>
bool readRegularFile(const std::filesystem::path& file, uint64_t maxBytes, bool noFollow, Bytes& out,
                     std::string& error);

// The same, throwing std::runtime_error "FILE: <what> is not a regular file (a FIFO)" on failure.
std::string readRegularFile(const std::filesystem::path& file, uint64_t maxBytes, const std::string& what);

// How a refusal names what it found: "a FIFO", "a character device", ... for a stat mode that is not a
// regular file; "N bytes is larger than the limit of M".
const char* fileKindName(unsigned mode);
std::string tooLargeReason(uint64_t size, uint64_t maxBytes);

// Whether path `p` lies inside folder `root` (both absolute and normal: weakly_canonical), by path components,
// so "/a/bc" is not inside "/a/b".
bool pathInside(const std::filesystem::path& root, const std::filesystem::path& p);

// A file that `header` names by `relative` (NRRD's data file, a VTK AMR set's blocks): resolved against the
// header's folder and confined to it. On failure returns an empty path and sets `error` ("is an absolute
// path; ...", "resolves outside ...").
std::filesystem::path resolveBeside(const std::filesystem::path& header, const std::string& relative, std::string& error);

}  // namespace ripple::apps
