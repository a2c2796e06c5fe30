// status_file.h — what a window just drew, for tools that drive a lab from outside.
//
// With LAB_STATUS_FILE=PATH in the environment, a lab in a window rewrites PATH after every
// frame with one line "frame=N width=W height=H" (N counts the frames drawn so far, W×H is the
// size they were drawn at). bench/soak.sh reads it to see that each input it sends is answered:
// a resize shows up as the new size, anything else as a frame drawn after it. When the lab has
// gone idle after its last frame and given its freed memory back (malloc_trim), the same line is
// rewritten with " idle" at its end: the moment the soak reads resident memory "at rest". Without
// the variable nothing is written.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace lab {

class StatusFile {
public:
    // nullptr when LAB_STATUS_FILE is not set.
    static std::unique_ptr<StatusFile> from_environment();
    explicit StatusFile(std::string path);

    // Called after each frame; the file is replaced whole (write + rename), never half-written.
    void frame_drawn(uint32_t width, uint32_t height);
    // Called when the window has gone idle after drawing (the frames done, freed memory given back).
    void went_idle();

private:
    void write(bool idle) const;

    std::string path_;
    uint64_t frames_ = 0;
    uint32_t width_ = 0, height_ = 0;
};

}  // namespace lab
