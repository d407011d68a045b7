// Video output through ffmpeg: raw 8-bit RGB frames on its standard input, the encoded file written by ffmpeg to an
// AtomicFile's temporary, renamed when ffmpeg succeeds. ffmpeg's messages go to an in-memory file and are quoted
// when it fails.
#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>

#include "animation_sinks.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/parse.hpp"

extern char** environ;

namespace tessera::detail {
namespace {

namespace fs = std::filesystem;

/// ffmpeg's muxer and encoder arguments for a video extension (lowercase).
std::vector<std::string> encoder_arguments(const std::string& ext, int crf) {
  if (ext == ".webm")  // VP9 in constant-quality mode (-b:v 0), multithreaded rows
    return {"-c:v",      "libvpx-vp9", "-crf",      std::to_string(crf < 0 ? 32 : crf),
            "-b:v",      "0",          "-row-mt",   "1",
            "-deadline", "good",       "-cpu-used", "4",
            "-pix_fmt",  "yuv420p",    "-f",        "webm"};
  std::vector<std::string> args = {
      "-c:v", "libx264", "-preset", "medium", "-crf", std::to_string(crf < 0 ? 20 : crf), "-pix_fmt", "yuv420p"};
  if (ext == ".mkv") {
    args.insert(args.end(), {"-f", "matroska"});
  } else {  // the index at the front, so a browser plays the file while it downloads
    args.insert(args.end(), {"-movflags", "+faststart", "-f", ext == ".mov" ? "mov" : "mp4"});
  }
  return args;
}

/// The first executable `name` in the folders of $PATH, as execvp would find it.
std::optional<fs::path> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::string_view rest = path;
  while (true) {
    const size_t colon = rest.find(':');
    const std::string folder(rest.substr(0, colon));
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    if (colon == std::string_view::npos) return std::nullopt;
    rest.remove_prefix(colon + 1);
  }
}

/// Writes all bytes to a pipe with SIGPIPE held back, so a reader that died gives EPIPE instead of killing this
/// process (a SIGPIPE raised by the write is consumed, one already pending is left alone). Returns 0 or the errno.
int write_to_pipe(int fd, const uint8_t* data, size_t size) {
  sigset_t pipe_signal, previous, pending;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  ::pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  sigpending(&pending);
  const bool was_pending = sigismember(&pending, SIGPIPE);
  int error = 0;
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error = errno;
      break;
    }
    data += n;
    size -= size_t(n);
  }
  if (error == EPIPE && !was_pending) {
    const timespec no_wait{};
    ::sigtimedwait(&pipe_signal, nullptr, &no_wait);
  }
  ::pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return error;
}

class VideoSink final : public Rgb8Sink {
 public:
  VideoSink(const fs::path& path, const AnimationOptions& options) : Rgb8Sink(options.srgb), path_(path) {
    encoder_ = encoder_arguments(lower_extension(path), options.crf);
    fps_ = fmt::format("{}", options.fps);
    const auto ffmpeg = find_on_path("ffmpeg");
    if (!ffmpeg)
      throw IoError(
          fmt::format("cannot write '{}': video output needs ffmpeg, which is not on PATH (install it, "
                      "e.g. `apt install ffmpeg`, or write a .gif or numbered PNG frames instead)",
                      printable(path.string())));
    ffmpeg_ = *ffmpeg;
    file_ = std::make_unique<AtomicFile>(path);
  }
  ~VideoSink() override {
    stop(true);
    if (messages_ >= 0) ::close(messages_);
  }
  VideoSink(const VideoSink&) = delete;
  VideoSink& operator=(const VideoSink&) = delete;

  void finish() override {
    const int status = stop(false);
    if (status != 0) fail(status);
    file_->commit();
  }

 protected:
  void write_rgb8(const std::vector<Rgb8>& pixels, int width, int height, long long index) override {
    // yuv420p needs even sizes: an odd last column or row is repeated. Even frames go to the pipe as they are.
    const int w = width + (width & 1), h = height + (height & 1);
    if (index == 0) start(w, h);
    static_assert(sizeof(Rgb8) == 3, "packed Rgb8 pixels are rgb24 bytes");
    std::span<const Rgb8> frame = pixels;
    if (w != width || h != height) {
      padded_.resize(size_t(w) * size_t(h));
      for (int y = 0; y < h; ++y) {
        const Rgb8* src = pixels.data() + size_t(std::min(y, height - 1)) * size_t(width);
        Rgb8* dst = padded_.data() + size_t(y) * size_t(w);
        for (int x = 0; x < w; ++x) dst[x] = src[std::min(x, width - 1)];
      }
      frame = padded_;
    }
    if (write_to_pipe(input_, &frame.data()->x, frame.size_bytes()) != 0) fail(stop(false));
  }

 private:
  /// Starts ffmpeg reading w x h rgb24 frames from a pipe and writing the AtomicFile's temporary.
  void start(int w, int h) {
    std::vector<std::string> args = {"ffmpeg",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-nostats",
                                     "-f",
                                     "rawvideo",
                                     "-pix_fmt",
                                     "rgb24",
                                     "-s",
                                     fmt::format("{}x{}", w, h),
                                     "-framerate",
                                     fps_,
                                     "-i",
                                     "pipe:0"};
    args.insert(args.end(), encoder_.begin(), encoder_.end());
    args.insert(args.end(), {"-y", file_->temporary().string()});
    std::vector<char*> argv;
    argv.reserve(args.size() + 1);
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw IoError(fmt::format("cannot start ffmpeg: {}", std::strerror(errno)));
    messages_ = ::memfd_create("ffmpeg-messages", MFD_CLOEXEC);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    if (messages_ >= 0) posix_spawn_file_actions_adddup2(&actions, messages_, 2);
    // The child starts with no signal blocked and SIGPIPE at its default action, whatever this process does.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, pipe_signal;
    sigemptyset(&none);
    sigemptyset(&pipe_signal);
    sigaddset(&pipe_signal, SIGPIPE);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &pipe_signal);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    const int error = ::posix_spawn(&pid_, ffmpeg_.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    ::close(pipe_fds[0]);
    input_ = pipe_fds[1];
    if (error != 0) {
      pid_ = -1;
      throw IoError(fmt::format("cannot start '{}': {}", ffmpeg_.string(), std::strerror(error)));
    }
  }

  /// Closes ffmpeg's input and waits for it (killing it first when `kill`); returns its wait status, 0 when none ran.
  int stop(bool kill) {
    if (input_ >= 0) ::close(input_), input_ = -1;
    if (pid_ <= 0) return 0;
    if (kill) ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return status;
  }

  /// Throws IoError for ffmpeg's wait status, quoting the end of its messages.
  [[noreturn]] void fail(int status) const {
    std::string messages;
    if (messages_ >= 0) {
      char buffer[4096];
      const off_t size = ::lseek(messages_, 0, SEEK_END);
      const off_t from = std::max<off_t>(0, size - off_t(sizeof buffer));
      const ssize_t n = ::pread(messages_, buffer, sizeof buffer, from);
      if (n > 0) messages.assign(buffer, size_t(n));
    }
    while (!messages.empty() && std::isspace(static_cast<unsigned char>(messages.back()))) messages.pop_back();
    const std::string how = WIFSIGNALED(status) ? fmt::format("was killed by signal {}", WTERMSIG(status))
                                                : fmt::format("failed with exit status {}", WEXITSTATUS(status));
    throw IoError(fmt::format("cannot write '{}': ffmpeg {}: {}", printable(path_.string()), how,
                              messages.empty() ? "(no message)" : printable(messages, 2000)));
  }

  fs::path path_, ffmpeg_;
  std::vector<std::string> encoder_;
  std::string fps_;
  std::unique_ptr<AtomicFile> file_;
  std::vector<Rgb8> padded_;  // an odd-sized frame with its last column and row repeated
  pid_t pid_ = -1;
  int input_ = -1, messages_ = -1;
};

}  // namespace

std::unique_ptr<AnimationSink> make_video_sink(const fs::path& path, const AnimationOptions& options) {
  return std::make_unique<VideoSink>(path, options);
}

}  // namespace tessera::detail
