#include "status_file.h"

#include <cstdio>

namespace lab::dev {

StatusFile::StatusFile(std::string path) : path_(std::move(path)) {}

void StatusFile::frame_drawn(uint32_t width, uint32_t height) {
    ++frames_;
    width_ = width;
    height_ = height;
    write(false);
}

void StatusFile::went_idle() { write(true); }

void StatusFile::write(bool idle) const {
    // A reader must never see half a line: write a temporary file, then rename it over the old one.
    const std::string temporary = path_ + ".tmp";
    if (std::FILE* f = std::fopen(temporary.c_str(), "w")) {
        std::fprintf(f, "frame=%llu width=%u height=%u%s\n", static_cast<unsigned long long>(frames_), width_,
                     height_, idle ? " idle" : "");
        if (std::fclose(f) == 0) std::rename(temporary.c_str(), path_.c_str());
    }
}

}  // namespace lab::dev
