// Removal of live temporaries on SIGINT / SIGTERM. The handler may only use
// async-signal-safe calls, so temporaries live in fixed slots it can read
// without locks.
#include <spiral/fileio.hpp>

#include "temporaries.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace spiral::fileio {

namespace {

struct Slot {
    std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live file, 3 live directory
    char path[4096] = {};
};
std::array<Slot, 32> slots;

void remove_directory_tree_signal_safe(const char* path) {
    const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        // getdents64 is a plain system call, unlike readdir.
        alignas(8) char buffer[4096];
        for (;;) {
            const long n = ::syscall(SYS_getdents64, fd, buffer, sizeof buffer);
            if (n <= 0) break;
            for (long offset = 0; offset < n;) {
                struct Entry {
                    std::uint64_t inode;
                    std::int64_t next;
                    unsigned short length;
                    unsigned char type;
                    char name[1];
                };
                const auto* entry = reinterpret_cast<const Entry*>(buffer + offset);
                const char* name = buffer + offset + offsetof(Entry, name);
                if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0)
                    ::unlinkat(fd, name, 0);
                offset += entry->length;
            }
        }
        ::close(fd);
    }
    ::rmdir(path);
}

void on_signal(int signal) {
    for (auto& slot : slots) {
        const int state = slot.state.load();
        if (state == 2) ::unlink(slot.path);
        if (state == 3) remove_directory_tree_signal_safe(slot.path);
    }
    // SA_RESETHAND restored the default action: die of the same signal.
    ::raise(signal);
}

// Checked at every registration (two cheap system calls), so a handler the
// program installs or removes later is respected either way.
void install_handlers() {
    for (int signal : {SIGINT, SIGTERM}) {
        struct sigaction current {};
        if (::sigaction(signal, nullptr, &current) != 0) continue;
        // A program with its own handler (or one ignoring the signal) keeps it.
        if (current.sa_handler != SIG_DFL || (current.sa_flags & SA_SIGINFO)) continue;
        // (ours, once installed, is not SIG_DFL, so it is installed once)
        struct sigaction action {};
        action.sa_handler = on_signal;
        sigemptyset(&action.sa_mask);
        action.sa_flags = SA_RESETHAND;
        ::sigaction(signal, &action, nullptr);
    }
}

}  // namespace

int register_temporary(const std::string& path, bool directory) {
    install_handlers();
    if (path.size() >= sizeof(Slot::path)) return -1;
    for (std::size_t i = 0; i < slots.size(); ++i) {
        int expected = 0;
        if (slots[i].state.compare_exchange_strong(expected, 1)) {
            std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
            slots[i].state.store(directory ? 3 : 2);
            return int(i);
        }
    }
    return -1;
}

void unregister_temporary(int slot) {
    if (slot >= 0) slots[std::size_t(slot)].state.store(0);
}

int pending_temporaries() {
    return int(std::count_if(slots.begin(), slots.end(),
                             [](const Slot& slot) { return slot.state.load() >= 2; }));
}

}  // namespace spiral::fileio
