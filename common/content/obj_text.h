// obj_text.h — the raw-text side of the OBJ loader (internal to lab_content, used by
// obj_model.cpp and mesh.cpp): reading a model or material file safely, the one-line
// error format, and ObjLineGate, the few checks per line that tinyobjloader cannot make,
// applied while tinyobjloader reads the text (so the text is read once, by it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

namespace lab::detail {

constexpr std::uintmax_t kMaxObjBytes = 1u << 30;   // 1 GiB
constexpr std::uintmax_t kMaxMtlBytes = 64u << 20;  // 64 MiB
constexpr double kMaxCoordinate = 1e6;              // |x| above this is rejected

// Throws std::runtime_error with the one line "FILE:LINE: reason" ("FILE: reason" for
// line 0); control characters become spaces so that it stays one line.
[[noreturn]] void fail(const std::string& file, size_t line, const std::string& reason);

// A piece of the input for a message: quoted, at most 40 characters, non-ASCII as '?'.
std::string quote(std::string_view s);

// Reads a whole regular file of at most `limit` bytes into `out`. Returns false if it
// cannot; `why` says why ("file not found", "file too large (N bytes)", ...).
bool read_small_file(const std::string& path, std::uintmax_t limit, std::string& out, std::string& why);

// Bytes that never occur in a text OBJ/MTL file (tab, CR, LF, FF, VT are fine).
bool is_binary_byte(unsigned char c);

// The OBJ text as tinyobjloader reads it: an std::streambuf that hands out one line at a
// time (with its line ending, exactly as in the file) and checks each line just before
// handing it out. A line that fails is not handed out: tinyobjloader sees the end of the
// file there, and error_line() / error() say what was wrong. The checks build nothing;
// they refuse only what tinyobjloader would silently misread (obj_text.cpp says what and why).
class ObjLineGate : public std::streambuf {
public:
    // [begin, end) must outlive the gate. It is only read (char*, not const char*, because
    // that is what std::streambuf's get area takes).
    ObjLineGate(char* begin, char* end);

    // The first line that failed a check (1-based; 0 = none so far) and why.
    size_t error_line() const { return error_line_; }
    const std::string& error() const { return error_; }

    // Checks the lines that tinyobjloader did not ask for: it stops early at an error of
    // its own (a negative joint in a `vw` line), and a file is still judged by its first
    // line that fails a check here, whatever tinyobjloader made of the lines before.
    void check_rest();

protected:
    int_type underflow() override;

private:
    bool next_line();                           // checks the next line; false at the end or a bad line
    std::string check(std::string_view line);  // "" = fine, else the reason
    std::string check_numbers(std::string_view key);
    std::string check_corners(std::string_view key);

    char* pos_;       // start of the next line to check
    char* end_;
    char* served_ = nullptr;  // [served_, pos_): the line handed out last
    size_t line_no_ = 0;      // lines end at \n, \r\n or \r, as in tinyobjloader
    long count_[3] = {0, 0, 0};  // v, vt, vn lines so far: what a face may refer to
    std::vector<std::string_view> tokens_;  // of the current line (kept: no allocation per line)
    size_t error_line_ = 0;
    std::string error_;
};

}  // namespace lab::detail
