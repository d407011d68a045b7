#include "tessera/core/atomic_file.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>
#include <streambuf>
#include <vector>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

// Temporaries that a fatal signal must remove. The handler may only call async-signal-safe functions, so the paths
// live in a fixed table of C strings: a writer claims a free slot (kFree -> kBusy), copies the path, then arms it
// (kArmed); the handler unlinks armed slots only. A path that does not fit, or a full table, is simply not
// registered (the exception and destructor paths still remove it).
constexpr int kFree = 0, kBusy = 1, kArmed = 2;
struct Slot {
  std::atomic<int> state{kFree};
  char path[4096] = {};
};
std::array<Slot, 64> g_slots;

extern "C" void remove_temporaries_and_reraise(int sig) {
  const int saved = errno;
  for (Slot& slot : g_slots)
    if (slot.state.load(std::memory_order_acquire) == kArmed) ::unlink(slot.path);
  errno = saved;
  // SA_RESETHAND restored the default action; the re-raised signal is delivered when the handler returns, so the
  // process ends with the signal as its status (a shell sees 128 + signal).
  ::raise(sig);
}

/// Installs the handler once, only where the signal still has its default action (an ignored SIGHUP under nohup
/// stays ignored, and a program's own handler is left alone).
void install_signal_cleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || (old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL) continue;
      struct sigaction sa {};
      sa.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&sa.sa_mask);
      sa.sa_flags = SA_RESETHAND;
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

int register_temporary(const std::filesystem::path& path) {
  std::error_code ec;
  const std::string absolute = std::filesystem::absolute(path, ec).string();
  if (ec || absolute.size() >= sizeof(Slot::path)) return -1;
  for (size_t i = 0; i < g_slots.size(); ++i) {
    int expected = kFree;
    if (g_slots[i].state.compare_exchange_strong(expected, kBusy, std::memory_order_acquire)) {
      std::memcpy(g_slots[i].path, absolute.c_str(), absolute.size() + 1);
      g_slots[i].state.store(kArmed, std::memory_order_release);
      return int(i);
    }
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_slots[size_t(slot)].state.store(kFree, std::memory_order_release);
}

/// 16 hex digits from the kernel's random source: a name nobody can predict.
std::string random_suffix() {
  unsigned char bytes[8];
  size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError(fmt::format("cannot draw a random temporary name: {}", std::strerror(errno)));
    got += size_t(n);
  }
  std::string hex;
  for (unsigned char b : bytes) hex += fmt::format("{:02x}", b);
  return hex;
}

/// An output stream buffer over a file descriptor; remembers the first write error.
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd), buffer_(size_t(1) << 16) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n <= epptr() - pptr()) {
      std::memcpy(pptr(), s, size_t(n));
      pbump(int(n));
      return n;
    }
    return drain() && write_all(s, size_t(n)) ? n : 0;  // large blocks bypass the buffer
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const bool ok = write_all(pbase(), size_t(pptr() - pbase()));
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return ok;
  }
  bool write_all(const char* data, size_t size) {
    while (size > 0 && error_ == 0) {
      const ssize_t n = ::write(fd_, data, size);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0)
        error_ = errno;
      else {
        data += n;
        size -= size_t(n);
      }
    }
    return error_ == 0;
  }
  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

}  // namespace

struct AtomicFile::State {
  std::filesystem::path target, temp;
  int fd = -1;
  int slot = -1;
  std::unique_ptr<FdBuffer> buffer;
  std::ostream out{nullptr};
  bool committed = false;
};

AtomicFile::AtomicFile(std::filesystem::path target) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.target = std::move(target);
  install_signal_cleanup();
  // The cleanup signals wait while the file is created and registered, so none can strand it in between.
  sigset_t cleanup_signals, previous;
  sigemptyset(&cleanup_signals);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&cleanup_signals, sig);
  ::pthread_sigmask(SIG_BLOCK, &cleanup_signals, &previous);
  struct Restore {
    const sigset_t& mask;
    ~Restore() { ::pthread_sigmask(SIG_SETMASK, &mask, nullptr); }
  } restore{previous};
  // O_EXCL fails on any existing name, a symlink included, and O_NOFOLLOW makes sure no link is ever followed; a
  // collision (a planted file or link) just draws another name.
  for (int attempt = 0; attempt < 16 && s.fd < 0; ++attempt) {
    s.temp = s.target.parent_path() / (s.target.filename().string() + ".tmp-" + random_suffix());
    s.fd = ::open(s.temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (s.fd < 0 && errno != EEXIST) break;
  }
  if (s.fd < 0) throw IoError(fmt::format("cannot create '{}': {}", s.target.string(), std::strerror(errno)));
  s.slot = register_temporary(s.temp);
  s.buffer = std::make_unique<FdBuffer>(s.fd);
  s.out.rdbuf(s.buffer.get());
}

AtomicFile::~AtomicFile() {
  State& s = *state_;
  if (s.fd >= 0) ::close(s.fd);
  if (!s.committed) ::unlink(s.temp.c_str());
  unregister_temporary(s.slot);
}

std::ostream& AtomicFile::stream() { return state_->out; }

const std::filesystem::path& AtomicFile::temporary() const { return state_->temp; }

void AtomicFile::commit() {
  State& s = *state_;
  s.out.flush();
  const int write_error = s.buffer->error();
  if (!s.out || write_error != 0)
    throw IoError(fmt::format("cannot write '{}': {}", s.target.string(),
                              write_error != 0 ? std::strerror(write_error) : "the stream failed"));
  const int fd = s.fd;
  s.fd = -1;
  if (::close(fd) != 0) throw IoError(fmt::format("cannot write '{}': {}", s.target.string(), std::strerror(errno)));
  std::error_code ec;
  std::filesystem::rename(s.temp, s.target, ec);
  if (ec) throw IoError(fmt::format("cannot write '{}': {}", s.target.string(), ec.message()));
  s.committed = true;
}

void write_file_atomic(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write) {
  AtomicFile file(target);
  write(file.stream());
  file.commit();
}

void write_file_atomic(const std::filesystem::path& target, std::string_view bytes) {
  write_file_atomic(target, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

std::string read_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError(fmt::format("cannot open '{}': {}", path.string(), std::strerror(errno)));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw IoError(fmt::format("cannot read '{}': {}", path.string(), std::strerror(errno)));
  // A folder opens fine on Linux and reports a meaningless size; say what it is instead.
  if (S_ISDIR(st.st_mode)) throw IoError(fmt::format("'{}': is a directory, expected a file", path.string()));
  std::string data;
  if (S_ISREG(st.st_mode)) data.reserve(size_t(st.st_size));
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError(fmt::format("cannot read '{}': {}", path.string(), std::strerror(errno)));
    if (n == 0) break;
    data.append(chunk, size_t(n));
  }
  return data;
}

}  // namespace tessera
