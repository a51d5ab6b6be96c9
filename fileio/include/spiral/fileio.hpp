#pragma once
// Output files for both programs (spiralgen's headers, deepgi's images and
// dumps), written so that a reader sees the old file or the whole new one,
// a failure leaves nothing behind, and a hostile directory cannot redirect
// the write. docs/hardening.md states the rules for special paths.
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace spiral::fileio {

// One line naming the path and the reason (errno text where there is one).
class WriteError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// An output being written. For a regular file (new or existing) it is a
// temporary created with O_CREAT | O_EXCL | O_NOFOLLOW and a random name in
// the target's directory; commit() syncs it, renames it over the target and
// syncs the directory. Until then the temporary is removed by the destructor,
// by any failure, and by SIGINT or SIGTERM.
//
// Special targets: "-" is standard output; a character device or FIFO
// (/dev/null, /dev/stdout) is written directly, never replaced; a symbolic
// link is followed and its target handled by these rules; a directory, a
// socket, an empty path, or an existing file we may not write (as cp would
// refuse it) is an error before anything is created.
class AtomicFile {
public:
    explicit AtomicFile(const std::filesystem::path& target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    // Every byte is written or WriteError is thrown (and the temporary removed).
    void write(const void* data, std::size_t size);
    void write(std::string_view text) { write(text.data(), text.size()); }
    void commit();

    // Where the data really goes (the symlink's target, or the path itself).
    const std::filesystem::path& destination() const { return destination_; }

private:
    [[noreturn]] void fail(std::string_view reason);
    void discard() noexcept;

    std::filesystem::path target_;       // as given, for messages
    std::filesystem::path destination_;  // after following symlinks
    std::string temporary_;              // empty when writing directly
    int fd_ = -1;
    int slot_ = -1;  // signal-cleanup registration
    bool direct_ = false;
    bool committed_ = false;
};

// The whole of `contents`, through AtomicFile.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// A directory of outputs that appears complete or not at all: files are
// written into a private temporary directory beside `target` (mkdtemp), and
// commit() syncs them and renames the directory into place. `target` must
// not exist, or be an empty directory, or hold only regular files whose names
// end in `replaceable_extension` (one ending, or several separated by spaces:
// ".pfm .png"; a previous set, swapped out whole and then removed); anything else is refused before
// a file is written. Until commit the temporary directory and its files are removed by the
// destructor, by any failure and by SIGINT or SIGTERM.
class AtomicDirectory {
public:
    explicit AtomicDirectory(const std::filesystem::path& target,
                             std::string_view replaceable_extension = {});
    ~AtomicDirectory();
    AtomicDirectory(const AtomicDirectory&) = delete;
    AtomicDirectory& operator=(const AtomicDirectory&) = delete;

    // Writes file `name` (no slashes) inside; WriteError names the final path.
    void write_file(std::string_view name, const void* data, std::size_t size);
    void commit();

private:
    void discard() noexcept;

    std::filesystem::path target_;
    std::string temporary_;
    int slot_ = -1;
    bool replace_existing_ = false;
    bool committed_ = false;
};

// The checks AtomicFile / AtomicDirectory make before creating anything, plus
// "the directory it goes into exists and is writable": for a program that
// wants to refuse a bad output path before doing its work.
void check_file_target(const std::filesystem::path& target);
void check_directory_target(const std::filesystem::path& target,
                            std::string_view replaceable_extension = {});

// Flushes and closes standard output, checking both: a program's printed
// output is an output like any other. Throws WriteError (a full disk, a
// closed descriptor, a broken pipe with SIGPIPE ignored). Call once, last.
void close_standard_output();

// For tests: the number of temporaries registered for signal cleanup now.
int pending_temporaries();

}  // namespace spiral::fileio
