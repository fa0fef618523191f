#include "app/cli/render_video.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/stat.h>
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

#include "engine/io/atomic_file.hpp"

extern char** environ;

namespace bhm::app {

namespace {

// A child's output goes to an in-memory file: never on the (possibly full) disk, and the child can
// write any amount without blocking on a pipe that nobody reads until it exits.
int memory_file(const std::string& path, const char* name) {
    const int fd = ::memfd_create(name, MFD_CLOEXEC);
    if (fd < 0) {
        const int error = errno;
        throw std::runtime_error(path + ": cannot capture " + name + "'s messages (" +
                                 engine::error_text(error) + ")");
    }
    return fd;
}

std::string contents_of(int fd) {
    std::string text;
    if (::lseek(fd, 0, SEEK_SET) != 0) return text;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
    }
    return text;
}

// The first non-empty line of a tool's messages: the cause; what follows are its consequences
// ("Could not write header ...: No space left on device", then "Error initializing output").
std::string first_line(const std::string& text) {
    const auto start = text.find_first_not_of(" \t\r\n");
    if (start == std::string::npos) return "";
    const auto end = text.find_first_of("\r\n", start);
    std::string line =
        text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t'))
        line.pop_back();
    return line;
}

// The last non-empty line of a tool's output (ffprobe's answer).
std::string last_line(const std::string& text) {
    const auto end = text.find_last_not_of(" \t\r\n");
    if (end == std::string::npos) return "";
    const auto start = text.find_last_of('\n', end);
    return text.substr(start == std::string::npos ? 0 : start + 1,
                       end + 1 - (start == std::string::npos ? 0 : start + 1));
}

int wait_for(int pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Captured {
    int status = -1;  //!< exit status, -1 when killed by a signal or not started
    std::string out, err;
};

// Runs a program with stdin from /dev/null and both outputs captured in memory.
Captured run_captured(const std::string& path, std::vector<std::string> args) {
    Captured result;
    const int out_fd = memory_file(path, "ffprobe"), err_fd = memory_file(path, "ffprobe");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, out_fd, STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, err_fd, STDERR_FILENO);
    std::vector<char*> argv;
    for (auto& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error == 0) {
        result.status = wait_for(pid);
        result.out = contents_of(out_fd);
        result.err = contents_of(err_fd);
    } else {
        result.err = "cannot start " + args[0] + ": " + engine::error_text(error);
    }
    ::close(out_fd);
    ::close(err_fd);
    return result;
}

}  // namespace

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
    stderr_fd_ = memory_file(path, "ffmpeg");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&actions, stderr_fd_, STDERR_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[1]);
    pid_t pid = -1;
    const int error = posix_spawn(&pid, ffmpeg->c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (error != 0) {
        ::close(fds[1]);
        ::close(stderr_fd_);
        stderr_fd_ = -1;
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
        wait_for(pid_);
    }
    if (stderr_fd_ >= 0) ::close(stderr_fd_);
    // Unfinished, failed or verified but never committed: the temporary goes, PATH stays.
    std::remove(temp_path_.c_str());
}

void VideoWriter::abandon(const std::string& why) {
    std::remove(temp_path_.c_str());
    throw std::runtime_error(path_ + ": " + why + "; the previous file is unchanged");
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
    ++frames_written_;
}

void VideoWriter::finish() {
    ::close(pipe_fd_);
    pipe_fd_ = -1;
    const int status = wait_for(pid_);
    pid_ = -1;
    const std::string messages = contents_of(stderr_fd_);
    ::close(stderr_fd_);
    stderr_fd_ = -1;
    // With -loglevel error, any message is an error, even when the exit status is 0 (a failed
    // trailer on a full disk is reported here but not in the status).
    const std::string said = first_line(messages);
    if (status != 0)
        abandon("ffmpeg failed (exit status " + std::to_string(status) + ")" +
                (said.empty() ? "" : ": " + said));
    if (!said.empty()) abandon("ffmpeg reported an error: " + said);
    // Written data that the kernel has not yet put on disk can still fail (delayed allocation on
    // a full disk): flush it and check, as engine/io/atomic_file does for our own files.
    const int fd = ::open(temp_path_.c_str(), O_RDONLY | O_CLOEXEC);
    struct stat info {};
    if (fd < 0 || ::fsync(fd) != 0 || ::fstat(fd, &info) != 0) {
        const int error = errno;
        if (fd >= 0) ::close(fd);
        abandon("cannot write the video (" + engine::error_text(error) + ")");
    }
    ::close(fd);
    if (info.st_size == 0) abandon("ffmpeg left an empty file");
    if (const auto ffprobe = find_on_path("ffprobe")) {
        // Decode every frame: a container without its index or with a cut-off stream either
        // errors or counts fewer frames than were sent.
        const Captured probe = run_captured(
            path_, {*ffprobe, "-v", "error", "-count_frames", "-select_streams", "v:0",
                    "-show_entries", "stream=nb_read_frames", "-of", "csv=p=0", temp_path_});
        const std::string counted = last_line(probe.out);
        const std::string complaint = first_line(probe.err);
        if (probe.status != 0 || !complaint.empty())
            abandon(
                "the video from ffmpeg is damaged (ffprobe: " +
                (complaint.empty() ? "exit status " + std::to_string(probe.status) : complaint) +
                ")");
        if (counted != std::to_string(frames_written_))
            abandon("the video from ffmpeg holds " + (counted.empty() ? "no" : counted) +
                    " frames, not the " + std::to_string(frames_written_) + " sent");
    }
    verified_ = true;
}

void VideoWriter::commit() {
    if (!verified_) throw std::logic_error(path_ + ": VideoWriter::commit before finish");
    std::error_code ec;
    std::filesystem::rename(temp_path_, path_, ec);
    if (ec) abandon("cannot move the video into place (" + ec.message() + ")");
}

}  // namespace bhm::app
