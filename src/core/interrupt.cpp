// Signal handling for interrupts (see interrupt.h). The handler only touches lock-free atomics and
// calls write(2), kill(2) and _exit(2), which are async-signal-safe.
#include "core/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>

namespace phos::interrupt {
namespace {

std::atomic<bool> g_requested{false};
std::atomic<int> g_signal{0};
std::atomic<int> g_count{0};
std::atomic<bool> g_silent{false};
std::atomic<bool> g_distributed{false};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);

std::atomic<int> g_watched{0};
int g_pids[kMaxWatchedRanks];  // written before g_watched is stored, read by the handler after

void say(const char* text) {
    if (g_silent.load()) return;
    const ssize_t n = ::write(STDERR_FILENO, text, std::strlen(text));
    (void)n;
}

// Says which watched ranks are no longer running; returns how many. Async-signal-safe.
int say_gone_ranks() {
    const int saved_errno = errno;
    int gone = 0;
    const int count = g_watched.load();
    for (int r = 1; r < count; ++r) {
        if (g_pids[r] <= 0 || ::kill(pid_t(g_pids[r]), 0) == 0 || errno != ESRCH) continue;
        char digits[16], *d = digits + sizeof digits;  // r in decimal
        *--d = '\0';
        unsigned v = unsigned(r);
        do *--d = char('0' + v % 10);
        while ((v /= 10) > 0);
        say(gone++ == 0 ? "\nphos: rank " : "phos: rank ");
        say(d);
        say(" has stopped running (killed, crashed or out of memory): the job ends without writing; "
            "images and checkpoints already written are intact\n");
    }
    errno = saved_errno;
    return gone;
}

extern "C" void on_signal(int signo) {
    if (g_count.fetch_add(1) > 0) {
        say("\nphos: interrupted again: exiting now (the image so far is not written)\n");
        ::_exit(exit_status(signo));
    }
    g_signal.store(signo);
    g_requested.store(true);
    if (g_distributed.load() && say_gone_ranks() > 0) return;
    if (g_distributed.load())
        say("\nphos: stopping every rank: finishing the current work and writing the image so far (nothing "
            "is written if a rank has died)\n");
    else
        say(signo == SIGTERM ? "\nphos: terminated: finishing the current work and writing the image so far\n"
                             : "\nphos: interrupted: finishing the current work and writing the image so far "
                               "(Ctrl-C again to quit at once)\n");
}

}  // namespace

void install_handlers(bool silent, bool distributed) {
    g_silent.store(silent);
    g_distributed.store(distributed);
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    std::signal(SIGXFSZ, SIG_IGN);
}

void watch_ranks(const int* pids, int count) {
    count = count < kMaxWatchedRanks ? count : kMaxWatchedRanks;
    g_watched.store(0);
    for (int r = 0; r < count; ++r) g_pids[r] = pids[r];
    g_watched.store(count);
}

bool requested() { return g_requested.load(std::memory_order_relaxed); }

int signal_number() { return g_signal.load(); }

void request(int signo) {
    g_count.fetch_add(1);
    g_signal.store(signo);
    g_requested.store(true);
}

void reset() {
    g_requested.store(false);
    g_signal.store(0);
    g_count.store(0);
}

int exit_status(int signo) { return 128 + (signo > 0 ? signo : SIGINT); }

}  // namespace phos::interrupt
