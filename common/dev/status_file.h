// status_file.h — what a window just drew, for tools that drive a lab from outside.
//
// With `--dev-status-file PATH`, a lab in a window rewrites PATH after every frame with one line
// "frame=N width=W height=H" (N counts the frames drawn so far, W×H is the size they were drawn
// at). bench/soak.py reads it to see that each input it sends is answered: a resize shows up as
// the new size, anything else as a frame drawn after it. When the lab has gone idle after its last
// frame and given its freed memory back (malloc_trim), the same line is rewritten with " idle" at
// its end: the moment the soak reads resident memory "at rest". Without the flag nothing is written.
#pragma once

#include <cstdint>
#include <string>

namespace lab::dev {

class StatusFile {
public:
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

}  // namespace lab::dev
