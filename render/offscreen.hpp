#pragma once
// Headless GL: an OSMesa (llvmpipe) OpenGL 3.3 core context and a framebuffer object, optionally
// multisampled, to draw into and read back. Needs no display.
#include <memory>
#include <string>

#include "render/image.hpp"

namespace bhm::render {

//! Destroy it before main returns (not as a static): Mesa's exit handlers run before static
//! destructors, and a context torn down after them can crash.
class OffscreenTarget {
  public:
    //! Creates the context (current afterwards, glad loaded) and a width x height target with
    //! up to `samples` samples per pixel (1 = no anti-aliasing). Throws std::runtime_error.
    OffscreenTarget(int width, int height, int samples = 4);
    ~OffscreenTarget();
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;

    //! Makes the context current and binds the target for drawing.
    void bind();
    //! New size; the contents are lost.
    void resize(int width, int height);
    //! Resolves the samples and reads the pixels, top row first, alpha 255.
    Image read_image();
    //! Reads into an existing image (no allocation once sized); for video frames.
    void read_image(Image& out);

    int width() const { return width_; }
    int height() const { return height_; }
    int samples() const { return samples_; }
    std::string gl_renderer() const;  //!< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

  private:
    struct State;
    std::unique_ptr<State> state_;
    int width_ = 0, height_ = 0, samples_ = 1;
    void create_framebuffers();
    void delete_framebuffers();
};

}  // namespace bhm::render
