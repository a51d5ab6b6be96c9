// Atomic outputs. The rules (docs/hardening.md): temporaries are created
// exclusively, never through a symlink, with unguessable names, beside the
// target so rename() stays within one file system; every write is checked;
// special files are written in place, never replaced.
#include <spiral/fileio.hpp>

#include "temporaries.hpp"

#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

namespace spiral::fileio {

namespace fs = std::filesystem;

namespace {

std::string errno_text(int error) {
    return std::strerror(error);
}

std::string random_suffix() {
    std::uint64_t value = 0;
    if (::getrandom(&value, sizeof value, 0) != sizeof value) {
        // Only unpredictability suffers; O_EXCL still refuses any planted name.
        static std::atomic<std::uint64_t> counter{0};
        value = (std::uint64_t(::getpid()) << 32) ^ counter.fetch_add(1) ^
                std::uint64_t(reinterpret_cast<std::uintptr_t>(&value));
    }
    return fmt::format("{:016x}", value);
}

fs::path directory_of(const fs::path& path) {
    return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

void sync_directory(const fs::path& directory) {
    const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);  // best effort: some file systems refuse fsync on directories
    ::close(fd);
}

// Follows symbolic links (at most 40, as the kernel does) to the path the
// data will really reach; a dangling link yields its missing target.
fs::path follow_links(const fs::path& path, const fs::path& target_for_messages) {
    fs::path current = path;
    for (int hop = 0; hop < 40; ++hop) {
        struct stat info {};
        if (::lstat(current.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return current;
        std::array<char, 4096> buffer{};
        const ssize_t length = ::readlink(current.c_str(), buffer.data(), buffer.size() - 1);
        if (length < 0)
            throw WriteError(fmt::format("cannot write '{}': {}", target_for_messages.string(),
                                         errno_text(errno)));
        const fs::path link(std::string(buffer.data(), std::size_t(length)));
        current = link.is_absolute() ? link : directory_of(current) / link;
    }
    throw WriteError(
        fmt::format("cannot write '{}': {}", target_for_messages.string(), errno_text(ELOOP)));
}

}  // namespace

// ---------------------------------------------------------------------------

AtomicFile::AtomicFile(const fs::path& target) : target_(target) {
    if (target.empty()) throw WriteError("cannot write '': empty path");
    if (target == "-") {
        // Whatever stdio holds for stdout goes first, to keep the order.
        if (std::fflush(stdout) != 0) fail(errno_text(errno));
        destination_ = target;
        fd_ = STDOUT_FILENO;
        direct_ = true;
        return;
    }
    // A special file reached through links (/dev/stdout is a link to
    // /proc/self/fd/1, whose target "pipe:[1234]" is no path) is opened
    // through the kernel's own resolution and written in place.
    if (struct stat through{};
        ::stat(target.c_str(), &through) == 0 &&
        (S_ISCHR(through.st_mode) || S_ISFIFO(through.st_mode) || S_ISSOCK(through.st_mode))) {
        destination_ = target;
        fd_ = ::open(target.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
        if (fd_ < 0) fail(errno_text(errno));
        direct_ = true;
        return;
    }
    destination_ = follow_links(target, target);
    struct stat info {};
    const bool exists = ::stat(destination_.c_str(), &info) == 0;
    if (!exists && errno != ENOENT) fail(errno_text(errno));
    if (exists) {
        if (S_ISDIR(info.st_mode)) fail("it is a directory");
        if (S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode)) {
            // /dev/null, /dev/stdout, a named pipe: written in place.
            fd_ = ::open(destination_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
            if (fd_ < 0) fail(errno_text(errno));
            direct_ = true;
            return;
        }
        if (!S_ISREG(info.st_mode)) fail("it is not a regular file, a character device or a FIFO");
        // As cp: an existing file we may not write is not ours to replace.
        if (::faccessat(AT_FDCWD, destination_.c_str(), W_OK, AT_EACCESS) != 0)
            fail(errno_text(errno));
    }
    const fs::path directory = directory_of(destination_);
    for (int attempt = 0;; ++attempt) {
        temporary_ = (directory /
                      fmt::format(".{}.tmp-{}", destination_.filename().string(), random_suffix()))
                         .string();
        slot_ = register_temporary(temporary_, false);
        // 0666: the umask decides, as for any new file.
        fd_ =
            ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd_ >= 0) break;
        const int error = errno;
        unregister_temporary(slot_);
        slot_ = -1;
        temporary_.clear();
        if (error != EEXIST || attempt > 100) fail(errno_text(error));
    }
    // Replacing a file keeps its permissions, as writing into it would.
    if (exists && ::fchmod(fd_, info.st_mode & 07777) != 0) fail(errno_text(errno));
}

AtomicFile::~AtomicFile() {
    if (!committed_) discard();
}

void AtomicFile::discard() noexcept {
    if (fd_ >= 0 && fd_ != STDOUT_FILENO) ::close(fd_);
    fd_ = -1;
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
    temporary_.clear();
    unregister_temporary(slot_);
    slot_ = -1;
}

void AtomicFile::fail(std::string_view reason) {
    discard();
    if (target_ == "-")
        throw WriteError(fmt::format("cannot write to standard output: {}", reason));
    throw WriteError(fmt::format("cannot write '{}': {}", target_.string(), reason));
}

void AtomicFile::write(const void* data, std::size_t size) {
    if (fd_ < 0) fail("the file is already closed");
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t written = ::write(fd_, bytes, size);
        if (written < 0) {
            if (errno == EINTR) continue;
            fail(errno_text(errno));
        }
        if (written == 0) fail(errno_text(ENOSPC));
        bytes += written;
        size -= std::size_t(written);
    }
}

void AtomicFile::commit() {
    if (fd_ < 0) fail("the file is already closed");
    if (direct_) {
        const int fd = fd_;
        fd_ = -1;
        if (fd != STDOUT_FILENO && ::close(fd) != 0) fail(errno_text(errno));
        committed_ = true;
        return;
    }
    // Data on disk before the name points at it, or a crash could leave an
    // empty file where the old one was.
    if (::fsync(fd_) != 0) fail(errno_text(errno));
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail(errno_text(errno));
    if (::rename(temporary_.c_str(), destination_.c_str()) != 0) fail(errno_text(errno));
    temporary_.clear();
    unregister_temporary(slot_);
    slot_ = -1;
    committed_ = true;
    sync_directory(directory_of(destination_));
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
    AtomicFile file(path);
    file.write(contents);
    file.commit();
}

// ---------------------------------------------------------------------------

namespace {

// True when every entry is a regular file named *`extension`.
// `extensions`: one or more endings separated by spaces (".pfm .png").
bool holds_only(const fs::path& directory, std::string_view extensions) {
    if (extensions.empty()) return false;
    auto has_listed_ending = [&](const std::string& name) {
        std::size_t start = 0;
        while (start < extensions.size()) {
            std::size_t end = extensions.find(' ', start);
            if (end == std::string_view::npos) end = extensions.size();
            const std::string_view ending = extensions.substr(start, end - start);
            if (!ending.empty() && name.size() > ending.size() &&
                name.compare(name.size() - ending.size(), ending.size(), ending) == 0)
                return true;
            start = end + 1;
        }
        return false;
    };
    std::error_code error;
    for (fs::directory_iterator it(directory, error), end; !error && it != end;
         it.increment(error)) {
        const std::string name = it->path().filename().string();
        if (it->symlink_status(error).type() != fs::file_type::regular || !has_listed_ending(name))
            return false;
    }
    return !error;
}

}  // namespace

namespace {

void require_writable_directory(const fs::path& directory, const std::string& message_prefix) {
    if (::faccessat(AT_FDCWD, directory.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
        throw WriteError(fmt::format("{}: directory '{}': {}", message_prefix, directory.string(),
                                     errno_text(errno)));
}

fs::path without_trailing_slash(fs::path path) {
    if (!path.has_filename() && path.has_parent_path()) path = path.parent_path();
    return path;
}

// Returns whether the target holds a previous set to replace.
bool check_directory(const fs::path& target, std::string_view replaceable_extension) {
    if (target.empty()) throw WriteError("cannot write directory '': empty path");
    auto fail = [&](std::string_view reason) {
        throw WriteError(fmt::format("cannot write directory '{}': {}", target.string(), reason));
    };
    bool replace_existing = false;
    struct stat info {};
    if (::lstat(target.c_str(), &info) == 0) {
        if (!S_ISDIR(info.st_mode)) fail("it exists and is not a directory");
        std::error_code error;
        const bool empty = fs::is_empty(target, error) && !error;
        replace_existing = !empty && holds_only(target, replaceable_extension);
        if (!empty && !replace_existing)
            fail(fmt::format(
                "it exists and holds other files than a previous set (the set is "
                "written whole into a new, empty or previous{} directory)",
                replaceable_extension.empty() ? std::string()
                                              : fmt::format(" {}", replaceable_extension)));
    } else if (errno != ENOENT) {
        fail(errno_text(errno));
    }
    require_writable_directory(directory_of(without_trailing_slash(target)),
                               fmt::format("cannot write directory '{}'", target.string()));
    return replace_existing;
}

}  // namespace

void check_directory_target(const fs::path& target, std::string_view replaceable_extension) {
    check_directory(target, replaceable_extension);
}

void check_file_target(const fs::path& target) {
    if (target == "-" || target.empty()) {
        AtomicFile probe(target);  // "-" creates nothing; "" throws
        return;
    }
    const fs::path destination = target;
    struct stat info {};
    if (::stat(destination.c_str(), &info) == 0 &&
        (S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode) || S_ISSOCK(info.st_mode))) {
        // Not opened now: opening a FIFO early would block, and closing it
        // would show its reader an end of file.
        if (::faccessat(AT_FDCWD, destination.c_str(), W_OK, AT_EACCESS) != 0)
            throw WriteError(
                fmt::format("cannot write '{}': {}", target.string(), errno_text(errno)));
        return;
    }
    // The regular-file checks, and creating the temporary proves the
    // directory writable; uncommitted, it is removed and the target untouched.
    AtomicFile probe(target);
}

AtomicDirectory::AtomicDirectory(const fs::path& target, std::string_view replaceable_extension)
    : target_(target) {
    replace_existing_ = check_directory(target, replaceable_extension);
    auto fail = [&](std::string_view reason) {
        throw WriteError(fmt::format("cannot write directory '{}': {}", target.string(), reason));
    };
    const fs::path clean = without_trailing_slash(target);
    std::string pattern =
        (directory_of(clean) / fmt::format(".{}.tmp-XXXXXX", clean.filename().string())).string();
    if (::mkdtemp(pattern.data()) == nullptr) fail(errno_text(errno));
    temporary_ = pattern;
    slot_ = register_temporary(temporary_, true);
    // mkdtemp makes it 0700; the finished set gets a normal directory's mode.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    if (::chmod(temporary_.c_str(), 0777 & ~mask) != 0) {
        const int error = errno;
        discard();
        fail(errno_text(error));
    }
}

AtomicDirectory::~AtomicDirectory() {
    if (!committed_) discard();
}

void AtomicDirectory::discard() noexcept {
    if (!temporary_.empty()) {
        std::error_code ignored;
        fs::remove_all(temporary_, ignored);
    }
    temporary_.clear();
    unregister_temporary(slot_);
    slot_ = -1;
}

void AtomicDirectory::write_file(std::string_view name, const void* data, std::size_t size) {
    const fs::path final_path = target_ / name;
    auto fail = [&](int error) {
        discard();
        throw WriteError(
            fmt::format("cannot write '{}': {}", final_path.string(), errno_text(error)));
    };
    if (temporary_.empty() || name.empty() || name.find('/') != std::string_view::npos ||
        name == "." || name == "..")
        fail(EINVAL);
    // The directory is private (made by mkdtemp), so O_EXCL alone suffices.
    const std::string path = temporary_ + "/" + std::string(name);
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) fail(errno);
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t written = ::write(fd, bytes, size);
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) {
            const int error = written == 0 ? ENOSPC : errno;
            ::close(fd);
            fail(error);
        }
        bytes += written;
        size -= std::size_t(written);
    }
    if (::fsync(fd) != 0) {
        const int error = errno;
        ::close(fd);
        fail(error);
    }
    if (::close(fd) != 0) fail(errno);
}

void AtomicDirectory::commit() {
    if (temporary_.empty())
        throw WriteError(
            fmt::format("cannot write directory '{}': already discarded", target_.string()));
    sync_directory(temporary_);
    if (replace_existing_) {
        // Swap the previous set out in one step, then remove it.
        if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) ==
            0) {
            discard();  // the temporary name now holds the previous set
            committed_ = true;
            return;
        }
        // Without RENAME_EXCHANGE: move the previous set aside first.
        const std::string aside = temporary_ + "-previous";
        if (::rename(target_.c_str(), aside.c_str()) == 0) {
            if (::rename(temporary_.c_str(), target_.c_str()) == 0) {
                temporary_ = aside;
                discard();
                committed_ = true;
                return;
            }
            ::rename(aside.c_str(), target_.c_str());
        }
    }
    // rename() replaces an empty directory, and fails if one appeared meanwhile
    // with files in it (ENOTEMPTY): the set never mixes with other files.
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
        const int error = errno;
        discard();
        throw WriteError(
            fmt::format("cannot write directory '{}': {}", target_.string(), errno_text(error)));
    }
    temporary_.clear();
    unregister_temporary(slot_);
    slot_ = -1;
    committed_ = true;
    sync_directory(directory_of(without_trailing_slash(target_)));
}

void close_standard_output() {
    // stdio buffers: a full disk, a closed descriptor or a broken pipe with
    // SIGPIPE ignored shows only here, after every print "succeeded".
    errno = 0;
    if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0)
        throw WriteError(fmt::format("cannot write to standard output: {}",
                                     errno_text(errno != 0 ? errno : EIO)));
    // Closing reports what the file system defers (NFS, quotas); a
    // descriptor closed before the program started, with nothing written to
    // it, is no failure.
    if (std::fclose(stdout) != 0 && errno != EBADF)
        throw WriteError(fmt::format("cannot write to standard output: {}", errno_text(errno)));
}

}  // namespace spiral::fileio
