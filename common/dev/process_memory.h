// process_memory.h — how the labs use glibc's heap on long runs (found and measured by the window
// soak, bench/soak.py; docs/testing.md "The window soak"). No effect on other C libraries.
#pragma once

namespace lab::dev {

// Gives the memory freed since the last call back to the system. Called when a window goes idle
// after drawing.
void give_back_free_memory();

}  // namespace lab::dev
