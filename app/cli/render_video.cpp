#include "app/cli/render_video.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace bhm::app {

std::optional<std::string> find_on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return std::nullopt;
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) continue;
        const std::string candidate = dir + "/" + program;
        if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate))
            return candidate;
    }
    return std::nullopt;
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps,
                         VideoFormat format)
    : path_(path),
      temp_path_(path + (format == VideoFormat::Gif ? ".tmp.gif" : ".tmp.mp4")),
      width_(width),
      height_(height) {
    const auto ffmpeg = find_on_path("ffmpeg");
    if (!ffmpeg)
        throw std::runtime_error(
            path +
            ": writing a video needs ffmpeg on PATH and none was found; install ffmpeg "
            "or write PNG frames with --frames N --out-dir DIR");
    char size[32], rate[32];
    std::snprintf(size, sizeof size, "%dx%d", width, height);
    std::snprintf(rate, sizeof rate, "%.6g", fps);
    std::vector<std::string> args = {*ffmpeg, "-hide_banner", "-loglevel", "error", "-y",
                                     "-f",    "rawvideo",     "-pix_fmt",  "rgba",  "-s",
                                     size,    "-r",           rate,        "-i",    "-"};
    if (format == VideoFormat::Gif) {
        // One palette for the whole animation, built from the frames themselves.
        for (const char* a :
             {"-vf", "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse", "-loop", "0",
              "-f", "gif"})
            args.emplace_back(a);
    } else {
        // H.264 needs even sizes: pad by one pixel when odd rather than refuse.
        for (const char* a : {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt",
                              "yuv420p", "-movflags", "+faststart", "-f", "mp4"})
            args.emplace_back(a);
    }
    args.push_back(temp_path_);
    std::vector<char*> argv;
    for (auto& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);

    // Close-on-exec: a second encoder started later (--video and --gif together) must not
    // inherit this pipe's write end, or this ffmpeg would never see the end of its input.
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
        throw std::runtime_error(path +
                                 ": cannot create a pipe to ffmpeg: " + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[1]);
    pid_t pid = -1;
    const int error = posix_spawn(&pid, ffmpeg->c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (error != 0) {
        ::close(fds[1]);
        throw std::runtime_error(path + ": cannot start " + *ffmpeg + ": " + std::strerror(error));
    }
    pid_ = pid;
    pipe_fd_ = fds[1];
    // A dead ffmpeg must surface as a write error, not kill us with SIGPIPE.
    ::signal(SIGPIPE, SIG_IGN);
}

VideoWriter::~VideoWriter() {
    if (pipe_fd_ >= 0) ::close(pipe_fd_);
    if (pid_ > 0) {
        ::kill(pid_, SIGTERM);
        int status = 0;
        ::waitpid(pid_, &status, 0);
        std::remove(temp_path_.c_str());
    }
}

void VideoWriter::write(const render::Image& frame) {
    if (frame.width != width_ || frame.height != height_)
        throw std::runtime_error(path_ + ": video frame size changed");
    const auto* data = frame.rgba.data();
    std::size_t left = frame.rgba.size();
    while (left > 0) {
        const ssize_t n = ::write(pipe_fd_, data, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            throw std::runtime_error(path_ +
                                     ": ffmpeg stopped reading frames: " + std::strerror(errno));
        data += n;
        left -= static_cast<std::size_t>(n);
    }
}

void VideoWriter::finish() {
    ::close(pipe_fd_);
    pipe_fd_ = -1;
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::remove(temp_path_.c_str());
        throw std::runtime_error(path_ + ": ffmpeg failed (exit status " +
                                 std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                                 ")");
    }
    std::error_code ec;
    std::filesystem::rename(temp_path_, path_, ec);
    if (ec) {
        const std::string reason = ec.message();  // before the clean-up can change errno
        std::remove(temp_path_.c_str());
        throw std::runtime_error(path_ + ": cannot move the video into place: " + reason);
    }
}

}  // namespace bhm::app
