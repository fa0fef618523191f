#pragma once
// Video output for bhm render: raw RGBA frames piped into an ffmpeg process (H.264 MP4, or an
// animated GIF with a palette made from the frames). The file is written as PATH.tmp.mp4 (or
// .tmp.gif) and only replaces PATH once it is verified: ffmpeg can exit 0 after failing to write
// its trailer on a full disk (issue 26 N1: a playable MP4 became a file without its moov atom,
// a GIF 0 bytes), so its exit status alone proves nothing. Verified means: exit status 0, nothing
// on its stderr (it runs with -loglevel error), the temporary flushed to disk (fsync) and not
// empty, and ffprobe (when on PATH) decodes exactly the frames that were sent, with no error.
#include <optional>
#include <string>

#include "render/image.hpp"

namespace bhm::app {

//! Full path of an executable found on PATH, or nothing.
std::optional<std::string> find_on_path(const std::string& program);

enum class VideoFormat { Mp4, Gif };

class VideoWriter {
  public:
    //! Starts ffmpeg reading width x height RGBA frames at fps. Throws std::runtime_error when
    //! ffmpeg is not on PATH or cannot be started.
    VideoWriter(const std::string& path, int width, int height, double fps,
                VideoFormat format = VideoFormat::Mp4);
    ~VideoWriter();  //!< abandons an unfinished video (kills ffmpeg, removes the temp file)
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    //! One frame of the size given at construction. Throws when ffmpeg went away.
    void write(const render::Image& frame);
    //! Closes the pipe, waits for ffmpeg and verifies the temporary (see above). Throws naming
    //! the file and ffmpeg's or ffprobe's own words on failure; the temporary is removed and
    //! the previous file at path is untouched.
    void finish();
    //! Moves the verified video into place (after finish(): several videos of one command are
    //! all verified before the first one replaces anything). Throws on failure.
    void commit();

  private:
    [[noreturn]] void abandon(const std::string& why);
    std::string path_, temp_path_;
    int width_, height_;
    long long frames_written_ = 0;
    int pipe_fd_ = -1;
    int stderr_fd_ = -1;  //!< an in-memory file (memfd) holding ffmpeg's stderr
    int pid_ = -1;
    bool verified_ = false;
};

}  // namespace bhm::app
