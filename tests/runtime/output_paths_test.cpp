// Output files under hostile conditions: a full disk, planted symlinks,
// special files, read-only targets, signals, and the --dump directory. The
// image writers (write_png / write_pfm) and deepgi itself are exercised, with
// the shared writer (fileio/) underneath. Risky cases run in child processes.
#include "../support/process.hpp"
#include "../support/skip.hpp"
#include "deepgi/image_io.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <spiral/fileio.hpp>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/sysmacros.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using spiral::test::make_scratch_dir;
using spiral::test::read_file;
using spiral::test::run_command;

namespace {

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

int entries_in(const fs::path& dir) {
    return int(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// A 64x64 grey image: its PNG is a few hundred bytes.
std::vector<std::uint8_t> grey_pixels() {
    return std::vector<std::uint8_t>(64 * 64 * 4, 128);
}

// Runs `body` in a child; returns its exit status (or 128 + signal).
template <typename Body>
int in_child(Body body) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        int status = 1;
        try {
            status = body();
        } catch (...) {
            status = 3;
        }
        ::_exit(status);
    }
    int raw = 0;
    ::waitpid(pid, &raw, 0);
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
}

// A write failure from the kernel, not from a test hook: RLIMIT_FSIZE makes
// write() fail with EFBIG past `bytes`, as a full disk fails with ENOSPC.
void limit_file_size(rlim_t bytes) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{bytes, bytes};
    ::setrlimit(RLIMIT_FSIZE, &limit);
}

std::string quoted(const fs::path& path) {
    return fmt::format("'{}'", path.string());
}

}  // namespace

TEST_CASE("output files: a failing write keeps the old file and leaves no temporary",
          "[runtime][output]") {
    const fs::path dir = make_scratch_dir("output-full");
    const fs::path png = dir / "image.png";
    write_text(png, "the good old image");
    const int status = in_child([&] {
        limit_file_size(100);  // the PNG needs a few hundred bytes
        try {
            deepgi::write_png(png, 64, 64, grey_pixels());
        } catch (const spiral::fileio::WriteError& error) {
            const std::string message = error.what();
            return message.find("File too large") != std::string::npos &&
                           message.find(png.string()) != std::string::npos
                       ? 0
                       : 4;
        }
        return 5;  // the write was said to succeed
    });
    REQUIRE(status == 0);
    REQUIRE(read_file(png) == "the good old image");
    REQUIRE(entries_in(dir) == 1);
    fs::remove_all(dir);
}

TEST_CASE("output files: deepgi on a full tmpfs exits 2 and keeps the old PNG",
          "[runtime][output]") {
    // A real full disk, where a private mount namespace can mount a tmpfs.
    if (run_command("unshare -rm true").status != 0) {
        spiral::test::skip_test(
            "unshare -rm is not available here (the RLIMIT_FSIZE case still covers the writer)");
    }
    const fs::path dir = make_scratch_dir("output-tmpfs");
    const fs::path script = dir / "full.sh";
    write_text(script, fmt::format(R"(set -u
mount -t tmpfs -o size=12k tmpfs {0}/mnt || exit 90
printf 'the good old image' > {0}/mnt/out.png
head -c 8000 /dev/zero > {0}/mnt/filler
{1} --headless --scene cornell --size 320x240 --output {0}/mnt/out.png 2> {0}/err
status=$?
ls -A {0}/mnt > {0}/listing
cat {0}/mnt/out.png > {0}/kept
exit $status
)",
                                   dir.string(), DEEPGI_EXECUTABLE));
    fs::create_directory(dir / "mnt");
    const auto result = run_command("unshare -rm sh " + quoted(script));
    INFO(read_file(dir / "err"));
    REQUIRE(result.status == 2);
    REQUIRE(read_file(dir / "kept") == "the good old image");
    REQUIRE(read_file(dir / "listing") == "filler\nout.png\n");
    REQUIRE(read_file(dir / "err").find("No space left on device") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("output files: symlinks planted at old temporary names redirect nothing",
          "[runtime][output]") {
    const fs::path dir = make_scratch_dir("output-symlink");
    const fs::path victim = dir / "victim";
    const fs::path png = dir / "out.png";
    write_text(victim, "precious");
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
        char byte = 0;
        ::close(ready[1]);
        if (::read(ready[0], &byte, 1) != 1) ::_exit(6);
        try {
            deepgi::write_png(png, 64, 64, grey_pixels());
            deepgi::write_pfm(dir / "out.pfm", deepgi::FloatImage{1, 1, 1, {0.5f}});
        } catch (...) {
            ::_exit(3);
        }
        ::_exit(0);
    }
    ::close(ready[0]);
    // Every name the writers used to derive from the pid, as an attacker
    // sharing the directory would plant them.
    for (const std::string name : {"out.png.tmp{}", "out.pfm.tmp{}", ".out.png.tmp.{}.0"})
        fs::create_symlink(victim, dir / fmt::format(fmt::runtime(name), pid));
    REQUIRE(::write(ready[1], "x", 1) == 1);
    ::close(ready[1]);
    int raw = 0;
    ::waitpid(pid, &raw, 0);
    REQUIRE(WIFEXITED(raw));
    REQUIRE(WEXITSTATUS(raw) == 0);
    REQUIRE(read_file(victim) == "precious");
    REQUIRE(read_file(png).substr(1, 3) == "PNG");
    REQUIRE(entries_in(dir) == 6);  // victim, two outputs, three planted links
    fs::remove_all(dir);
}

TEST_CASE("output files: devices, FIFOs and symlinks are written through, never replaced",
          "[runtime][output]") {
    const fs::path dir = make_scratch_dir("output-special");
    // A symlink to a file: the file gets the image, the link stays a link.
    write_text(dir / "real.png", "old");
    fs::create_symlink("real.png", dir / "link.png");
    deepgi::write_png(dir / "link.png", 64, 64, grey_pixels());
    REQUIRE(fs::is_symlink(dir / "link.png"));
    REQUIRE(read_file(dir / "real.png").substr(1, 3) == "PNG");
    // A symlink to /dev/null (as /dev/stdout is to a descriptor): stays a link.
    fs::create_symlink("/dev/null", dir / "null-link");
    deepgi::write_png(dir / "null-link", 64, 64, grey_pixels());
    REQUIRE(fs::is_symlink(dir / "null-link"));
    REQUIRE(fs::is_character_file("/dev/null"));
    // A FIFO: its reader gets the whole PNG, and it is still a FIFO.
    REQUIRE(::mkfifo((dir / "pipe").c_str(), 0600) == 0);
    std::string received;
    std::thread reader([&] { received = read_file(dir / "pipe"); });
    deepgi::write_png(dir / "pipe", 64, 64, grey_pixels());
    reader.join();
    REQUIRE(fs::is_fifo(dir / "pipe"));
    REQUIRE(received == read_file(dir / "real.png"));
    // A character device of our own (root only): /dev/null's numbers.
    if (::mknod((dir / "null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
        deepgi::write_png(dir / "null", 64, 64, grey_pixels());
        REQUIRE(fs::is_character_file(dir / "null"));
    }
    // Directories, sockets' kin, and empty paths are refused.
    REQUIRE_THROWS_AS(deepgi::write_png(dir, 64, 64, grey_pixels()), spiral::fileio::WriteError);
    REQUIRE_THROWS_AS(deepgi::write_png("", 64, 64, grey_pixels()), spiral::fileio::WriteError);
    fs::remove_all(dir);
}

TEST_CASE("output files: '-' is standard output", "[runtime][output]") {
    const fs::path dir = make_scratch_dir("output-stdout");
    const int status = in_child([&] {
        std::fflush(stdout);  // the test runner's own output is not ours to capture
        const int fd = ::open((dir / "captured").c_str(), O_WRONLY | O_CREAT, 0600);
        ::dup2(fd, STDOUT_FILENO);
        deepgi::write_png("-", 64, 64, grey_pixels());
        return 0;
    });
    REQUIRE(status == 0);
    const auto png = deepgi::encode_png(64, 64, grey_pixels());
    REQUIRE(read_file(dir / "captured") == std::string(png.begin(), png.end()));
    REQUIRE(entries_in(dir) == 1);  // no file named '-'
    fs::remove_all(dir);
}

TEST_CASE("output files: a read-only file of someone else is not replaced", "[runtime][output]") {
    const fs::path dir = make_scratch_dir("output-readonly");
    fs::permissions(dir, fs::perms::all);  // a shared, writable directory
    const fs::path png = dir / "theirs.png";
    write_text(png, "not yours");
    fs::permissions(png, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
    const int status = in_child([&] {
        // As root the file would be writable (cp would write it too): drop to nobody.
        if (::geteuid() == 0 && ::setuid(65534) != 0) return 7;
        try {
            deepgi::write_png(png, 64, 64, grey_pixels());
        } catch (const spiral::fileio::WriteError& error) {
            return std::string(error.what()).find("Permission denied") != std::string::npos ? 0 : 4;
        }
        return 5;
    });
    REQUIRE(status == 0);
    REQUIRE(read_file(png) == "not yours");
    REQUIRE(entries_in(dir) == 1);
    fs::remove_all(dir);
}

TEST_CASE("output files: SIGTERM or SIGINT mid-write removes the temporaries",
          "[runtime][output]") {
    for (int signal : {SIGTERM, SIGINT}) {
        const fs::path dir = make_scratch_dir("output-signal");
        int ready[2];
        REQUIRE(::pipe(ready) == 0);
        const pid_t pid = ::fork();
        if (pid == 0) {
            std::signal(SIGINT, SIG_DFL);  // Catch2 installs its own handlers
            std::signal(SIGTERM, SIG_DFL);
            spiral::fileio::AtomicFile file(dir / "out.png");
            file.write("partial", 7);
            spiral::fileio::AtomicDirectory dump(dir / "dump");
            dump.write_file("a.pfm", "x", 1);
            if (::write(ready[1], "x", 1) != 1) ::_exit(6);
            ::pause();
            ::_exit(0);
        }
        char byte = 0;
        REQUIRE(::read(ready[0], &byte, 1) == 1);
        REQUIRE(entries_in(dir) == 2);  // the two temporaries exist now
        ::kill(pid, signal);
        int raw = 0;
        ::waitpid(pid, &raw, 0);
        ::close(ready[0]);
        ::close(ready[1]);
        REQUIRE(WIFSIGNALED(raw));
        REQUIRE(WTERMSIG(raw) == signal);
        REQUIRE(entries_in(dir) == 0);
        fs::remove_all(dir);
    }
}

TEST_CASE("dump directory: checked first, written whole, failures name the file",
          "[runtime][output]") {
    const fs::path dir = make_scratch_dir("output-dump");
    using spiral::fileio::AtomicDirectory;
    using spiral::fileio::WriteError;
    // Onto an existing file, or a directory of other files: refused up front.
    write_text(dir / "file", "keep");
    REQUIRE_THROWS_AS(AtomicDirectory(dir / "file", ".pfm"), WriteError);
    fs::create_directory(dir / "mine");
    write_text(dir / "mine" / "notes.txt", "keep");
    REQUIRE_THROWS_AS(AtomicDirectory(dir / "mine", ".pfm"), WriteError);
    REQUIRE(entries_in(dir) == 2);
    // A previous dump (.pfm files only) is replaced whole.
    {
        AtomicDirectory first(dir / "dump", ".pfm");
        first.write_file("a.pfm", "1", 1);
        first.write_file("b.pfm", "1", 1);
        first.commit();
    }
    {
        AtomicDirectory second(dir / "dump", ".pfm");
        second.write_file("a.pfm", "2", 1);
        second.commit();
    }
    REQUIRE(read_file(dir / "dump" / "a.pfm") == "2");
    REQUIRE(!fs::exists(dir / "dump" / "b.pfm"));
    REQUIRE(entries_in(dir) == 3);
    // A write failing half-way: nothing appears, the previous set stays,
    // and the message names the file and the reason.
    const int status = in_child([&] {
        limit_file_size(1000);
        AtomicDirectory third(dir / "dump", ".pfm");
        third.write_file("a.pfm", "3", 1);
        const std::string big(5000, 'x');
        try {
            third.write_file("big.pfm", big.data(), big.size());
        } catch (const WriteError& error) {
            const std::string message = error.what();
            return message.find((dir / "dump" / "big.pfm").string()) != std::string::npos &&
                           message.find("File too large") != std::string::npos
                       ? 0
                       : 4;
        }
        return 5;
    });
    REQUIRE(status == 0);
    REQUIRE(read_file(dir / "dump" / "a.pfm") == "2");
    REQUIRE(entries_in(dir) == 3);
    fs::remove_all(dir);
}

TEST_CASE("deepgi: a bad --dump fails before the PNG is written", "[runtime][output][cli]") {
    const fs::path dir = make_scratch_dir("output-deepgi-dump");
    write_text(dir / "dump-is-a-file", "keep");
    write_text(dir / "out.png", "the good old image");
    const auto result = run_command(
        fmt::format("{} --headless --scene cornell --size 64x48 --output {} --dump {}",
                    DEEPGI_EXECUTABLE, quoted(dir / "out.png"), quoted(dir / "dump-is-a-file")));
    REQUIRE(result.status == 2);
    REQUIRE(result.err.find("dump-is-a-file") != std::string::npos);
    REQUIRE(read_file(dir / "out.png") == "the good old image");
    REQUIRE(entries_in(dir) == 2);
    // The same with a writable dump directory writes both.
    const auto ok =
        run_command(fmt::format("{} --headless --scene cornell --size 64x48 --output {} --dump {}",
                                DEEPGI_EXECUTABLE, quoted(dir / "out.png"), quoted(dir / "dump")));
    INFO(ok.err);
    REQUIRE(ok.status == 0);
    REQUIRE(read_file(dir / "out.png").substr(1, 3) == "PNG");
    REQUIRE(deepgi::read_pfm(dir / "dump" / "tonemap-colour.pfm").width == 64);
    fs::remove_all(dir);
}
