#include "framework/core/fatal_signal_report.h"

#include "framework/core/error.h"

#include <fmt/format.h>

#include <atomic>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <mutex>
#include <string_view>

#include <fcntl.h>
#include <unistd.h>

namespace bvhlab {
namespace {

constexpr int kFatalSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
struct sigaction previousActions[std::size(kFatalSignals)];

std::atomic<int> reportFd{STDERR_FILENO};
std::atomic<const PluginCall*> processCall{nullptr};

// Enough for the handler's formatting and the kernel's signal frame (AVX-512 state included).
constexpr size_t kSignalStackBytes = 64 * 1024;

// A signal stack for the calling thread, released when the thread ends. A stack set already
// (Python's faulthandler sets one) is kept.
class SignalStack {
public:
    SignalStack() {
        stack_t current{};
        if (sigaltstack(nullptr, &current) != 0 || !(current.ss_flags & SS_DISABLE)) return;
        memory_ = std::make_unique<char[]>(kSignalStackBytes);
        stack_t mine{};
        mine.ss_sp = memory_.get();
        mine.ss_size = kSignalStackBytes;
        if (sigaltstack(&mine, nullptr) != 0) memory_.reset();
    }
    ~SignalStack() {
        if (!memory_) return;
        stack_t off{};
        off.ss_flags = SS_DISABLE;
        sigaltstack(&off, nullptr);
    }
    SignalStack(const SignalStack&) = delete;
    SignalStack& operator=(const SignalStack&) = delete;

private:
    std::unique_ptr<char[]> memory_;
};

}  // namespace

// The thread's running plugin call, and whether the thread has its signal stack: one
// thread_local, so that a scope looks up this library's thread storage (a call through
// __tls_get_addr) once, and its end not at all.
struct PluginCallScope::Thread {
    const PluginCall* running = nullptr;
    bool hasSignalStack = false;
};

namespace {

thread_local PluginCallScope::Thread thisThread;

void giveThreadASignalStack() {
    static thread_local SignalStack stack;
    thisThread.hasSignalStack = true;
}

// The report's line, formatted on the signal stack without allocating. vsnprintf is not on
// POSIX's list of async-signal-safe functions; it does not allocate for these formats, and a
// report that might fail beats none.
class ReportLine {
public:
    void append(const char* format, ...) __attribute__((format(printf, 2, 3))) {
        va_list args;
        va_start(args, format);
        const int n = std::vsnprintf(text_ + size_, sizeof(text_) - size_, format, args);
        va_end(args);
        if (n > 0) size_ = std::min(sizeof(text_) - 1, size_ + size_t(n));
    }
    void appendSignal(int signal) {
        const char* name = sigabbrev_np(signal);
        const char* meaning = sigdescr_np(signal);
        if (name && meaning)
            append("SIG%s (%s)", name, meaning);
        else
            append("signal %d", signal);
    }
    void appendCall(const PluginCall& c) {
        append(" in plugin %s, accelerator '%s': %s", c.plugin, c.accelerator, c.call);
        if (c.ray) {
            const Ray& r = *c.ray;
            if (c.count == 1)
                append(" of the ray");
            else
                append(" of %zu rays, the first", c.count);
            append(" org=(%.9g, %.9g, %.9g) dir=(%.9g, %.9g, %.9g) t in [%.9g, %.9g]", r.org.x, r.org.y, r.org.z,
                   r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax);
        } else if (c.count > 0) {
            append(" over %zu primitives", c.count);
        }
    }
    std::string_view text() const { return {text_, size_}; }
    void writeTo(int fd) const {
        for (size_t done = 0; done < size_;) {
            const ssize_t n = ::write(fd, text_ + done, size_ - done);
            if (n <= 0) return;
            done += size_t(n);
        }
    }

private:
    char text_[1024];
    size_t size_ = 0;
};

void onFatalSignal(int signal, siginfo_t*, void*) {
    const int fd = reportFd.load();
    ReportLine line;
    if (fd == STDERR_FILENO) line.append("bvhlab: ");
    line.appendSignal(signal);
    if (const PluginCall* running = thisThread.running) {
        line.appendCall(*running);
    } else if (const PluginCall* other = processCall.load()) {
        line.append(" on a thread other than the call's");
        line.appendCall(*other);
    } else {
        line.append(", outside any plugin call");
    }
    line.append("\n");
    line.writeTo(fd);
    // The signal, blocked while this handler runs, is delivered again to the action that was
    // there before: the process dies of it.
    for (size_t i = 0; i < std::size(kFatalSignals); ++i)
        if (kFatalSignals[i] == signal) sigaction(signal, &previousActions[i], nullptr);
    raise(signal);
}

}  // namespace

PluginCallScope::PluginCallScope(const PluginCall& call) : call_(&call), thread_(&thisThread) {
    previous_ = thread_->running;
    if (!thread_->hasSignalStack) giveThreadASignalStack();
    thread_->running = &call;
    if (!call.ray) processCall.store(&call);
}

PluginCallScope::~PluginCallScope() {
    thread_->running = previous_;
    if (!call_->ray) {
        const PluginCall* expected = call_;
        processCall.compare_exchange_strong(expected, nullptr);
    }
}

void installFatalSignalReport() {
    static std::once_flag installed;
    std::call_once(installed, [] {
        struct sigaction action {};
        action.sa_sigaction = onFatalSignal;
        action.sa_flags = SA_SIGINFO | SA_ONSTACK;
        sigemptyset(&action.sa_mask);
        for (size_t i = 0; i < std::size(kFatalSignals); ++i) sigaction(kFatalSignals[i], &action, &previousActions[i]);
    });
}

void reportFatalSignalsTo(const std::filesystem::path& file) {
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError(fmt::format("{}: cannot write: {}", file.string(), std::strerror(errno)));
    const int old = reportFd.exchange(fd);
    if (old != STDERR_FILENO) ::close(old);
}

std::string signalDescription(int signal) {
    ReportLine line;
    line.appendSignal(signal);
    return std::string(line.text());
}

}  // namespace bvhlab
