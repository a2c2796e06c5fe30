// test_process_memory.cpp — common/dev/process_memory.h really changes how glibc's heap behaves
// (the window soak found it; a build where it silently compiles to nothing must fail).
#include "process_memory.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#ifdef __GLIBC__
#include <malloc.h>

namespace {
// Keeps the compiler from dropping a malloc / free pair whose memory is never read.
void* kept(void* p) {
    asm volatile("" : : "r"(p) : "memory");
    return p;
}

long resident_kib() {
    long pages = 0, resident = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return resident * 4;  // 4 KiB pages
}
}  // namespace

// 32 MiB of small blocks freed behind one that stays: free() cannot shrink the heap past the live
// block, so the pages stay resident until give_back_free_memory() returns them.
TEST(ProcessMemory, FreedHeapPagesGoBack) {
    std::vector<void*> blocks;
    for (int i = 0; i < 32 * 1024; ++i) {
        blocks.push_back(kept(std::malloc(1000)));
        static_cast<char*>(blocks.back())[0] = 1;
        kept(blocks.back());
    }
    void* last = kept(std::malloc(1000));
    for (void* b : blocks) std::free(b);
    const long before = resident_kib();
    lab::dev::give_back_free_memory();
    const long after = resident_kib();
    EXPECT_LT(after, before - 16 * 1024) << "resident " << before << " KiB -> " << after << " KiB";
    std::free(last);
}
#else
TEST(ProcessMemory, NotGlibc) { GTEST_SKIP() << "the settings are glibc's; this C library keeps its own"; }
#endif
