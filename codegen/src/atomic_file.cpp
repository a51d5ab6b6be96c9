// Write-to-temporary-then-rename, so a reader (or a build tool checking
// timestamps) never sees a half-written header, and a failed run leaves the
// previous file exactly as it was.
#include <spiral/codegen.hpp>

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace spiral::codegen {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, std::string_view problem) {
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path.string(), problem));
}

// Closes and unlinks the temporary unless release() was called after the rename.
struct TemporaryFile {
    std::string name;
    int fd = -1;
    bool renamed = false;

    ~TemporaryFile() {
        if (fd >= 0) ::close(fd);
        if (!renamed && !name.empty()) ::unlink(name.c_str());
    }
};

std::string errno_text(int error) {
    return std::strerror(error);
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
    if (path.empty()) fail(path, "empty path");
    if (!path.has_filename()) fail(path, "path names a directory, not a file");
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) fail(path, "it is a directory");

    // A hidden sibling of the target: same directory, so rename() is atomic
    // (same file system), and the pid plus a counter keep concurrent writers
    // (parallel build rules, threads) apart. O_EXCL refuses a stale leftover.
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path directory = path.parent_path();
    TemporaryFile temporary;
    for (int attempt = 0;; ++attempt) {
        const std::filesystem::path candidate =
            directory / fmt::format(".{}.tmp.{}.{}", path.filename().string(),
                                    static_cast<long>(::getpid()), counter.fetch_add(1));
        // 0666 lets the umask decide the final permissions, as for any new file.
        const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            temporary.name = candidate.string();
            temporary.fd = fd;
            break;
        }
        if (errno != EEXIST || attempt > 100)
            fail(path,
                 fmt::format("cannot create a temporary file in '{}': {}",
                             directory.empty() ? "." : directory.string(), errno_text(errno)));
    }

    const char* data = contents.data();
    std::size_t left = contents.size();
    while (left > 0) {
        const ssize_t written = ::write(temporary.fd, data, left);
        if (written < 0) {
            if (errno == EINTR) continue;
            fail(path, errno_text(errno));
        }
        data += written;
        left -= static_cast<std::size_t>(written);
    }
    if (::fsync(temporary.fd) != 0) fail(path, errno_text(errno));
    const int fd = temporary.fd;
    temporary.fd = -1;
    if (::close(fd) != 0) fail(path, errno_text(errno));
    if (::rename(temporary.name.c_str(), path.c_str()) != 0) fail(path, errno_text(errno));
    temporary.renamed = true;
}

void write_stdout(std::string_view contents) {
    errno = 0;
    const std::size_t written = std::fwrite(contents.data(), 1, contents.size(), stdout);
    if (written != contents.size() || std::fflush(stdout) != 0 || std::ferror(stdout))
        throw std::runtime_error(fmt::format("cannot write to standard output: {}",
                                             errno != 0 ? errno_text(errno) : "write failed"));
}

}  // namespace spiral::codegen
