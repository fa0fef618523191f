#pragma once
// Video output for bhm render: raw RGBA frames piped into an ffmpeg process (H.264 MP4, or an
// animated GIF with a palette made from the frames). The file is written as PATH.tmp.mp4 (or
// .tmp.gif) and renamed when ffmpeg succeeds.
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
    //! Closes the pipe, waits for ffmpeg and moves the file into place. Throws with ffmpeg's
    //! exit status on failure.
    void finish();

  private:
    std::string path_, temp_path_;
    int width_, height_;
    int pipe_fd_ = -1;
    int pid_ = -1;
};

}  // namespace bhm::app
