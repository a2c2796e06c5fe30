// process_memory.h — how the labs use glibc's heap on long runs (found and measured by the window
// soak, bench/soak.py; docs/testing.md "The window soak"). No effect on other C libraries.
#pragma once

namespace lab::dev {

// Big blocks (images, swapchain and staging memory: lavapipe mallocs them) straight from the OS
// and back to it when freed. Called once at start-up.
void keep_big_blocks_out_of_the_heap();

// Gives the memory freed since the last call back to the system. Called when a window goes idle
// after drawing.
void give_back_free_memory();

}  // namespace lab::dev
