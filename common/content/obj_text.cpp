// obj_text.cpp — reading OBJ/MTL files, the error format, and the per-line checks of
// ObjLineGate (see obj_text.h).
//
// Why these checks need the text: tinyobjloader (2.0.0rc10, /usr/include/tiny_obj_loader.h)
// returns no line numbers, and the mistakes below leave no trace in what it returns:
//   * numbers (`v`/`vt`/`vn`): parseReal() stores 0 (or the default) for a token it cannot
//     read (`nan`, `inf`, `1e`) or that is missing (a truncated line), and stops at the
//     first bad character (`0x` reads as 0): a stored 0 cannot tell "0" from "garbage".
//   * corners (`f`/`l`/`p`): indices are read with atoi() (99999999999999999999 reads as
//     −1, the last vertex; `1/x` or `1/2/3/4` is reported as a "zero value" at best), and
//     positive indices are not compared with what was read so far: a forward reference
//     passes, one past the end gives a warning at the end of the file (and a quad with it
//     is dropped).
//     A face with 0–2 corners is skipped or dropped with a warning that has no line.
//   * polygons are ear-clipped while the file is read, in up to ~corners³ steps: a
//     5000-corner face has to be refused before tinyobjloader reads it, not after.
// So each `v`/`vt`/`vn`/`f`/`l`/`p` line is checked here, token by token, just before
// tinyobjloader reads it; any other line (g, o, s, usemtl, mtllib, ...) only for binary
// bytes. obj_model.cpp checks what tinyobjloader returns once more (without line numbers).
#include "obj_text.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace lab::detail {
namespace {

constexpr size_t kMaxFaceCorners = 4096;  // ear clipping costs ~corners² per face

// A whole token as a number ("+1.5e3" too; anything left over is an error).
bool parse_double(std::string_view tok, double& out) {
    if (tok.size() > 1 && tok[0] == '+' && tok[1] != '-') tok.remove_prefix(1);
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    if (ec == std::errc::result_out_of_range) out = std::numeric_limits<double>::infinity();
    return !tok.empty() && end == tok.data() + tok.size() && (ec == std::errc() || ec == std::errc::result_out_of_range);
}

bool parse_index(std::string_view tok, long& out) {
    if (tok.size() > 1 && tok[0] == '+' && tok[1] != '-') tok.remove_prefix(1);
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    return !tok.empty() && ec == std::errc() && end == tok.data() + tok.size();
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }  // tinyobjloader's separators

}  // namespace

[[noreturn]] void fail(const std::string& file, size_t line, const std::string& reason) {
    std::string msg = file;
    if (line > 0) msg += ":" + std::to_string(line);
    msg += ": " + reason;
    for (char& ch : msg) {
        if (static_cast<unsigned char>(ch) < 0x20) ch = ' ';  // keep it one line
    }
    throw std::runtime_error(msg);
}

std::string quote(std::string_view s) {
    std::string q(s.substr(0, 40));
    for (char& ch : q) {
        const unsigned char u = static_cast<unsigned char>(ch);
        if (u < 0x20 || u >= 0x7f) ch = '?';
    }
    return "'" + q + (s.size() > 40 ? "...'" : "'");
}

bool read_small_file(const std::string& path, std::uintmax_t limit, std::string& out, std::string& why) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) { why = "file not found"; return false; }
    // Only regular files: `mtllib /dev/zero` or a FIFO would never end.
    if (!std::filesystem::is_regular_file(path, ec)) { why = "not a regular file"; return false; }
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) { why = "cannot read file size"; return false; }
    if (size > limit) { why = "file too large (" + std::to_string(size) + " bytes)"; return false; }
    std::ifstream in(path, std::ios::binary);
    if (!in) { why = "cannot open file"; return false; }
    out.resize(static_cast<size_t>(size));
    in.read(out.data(), static_cast<std::streamsize>(size));
    if (static_cast<std::uintmax_t>(in.gcount()) != size) { why = "read error"; return false; }
    return true;
}

bool is_binary_byte(unsigned char c) {
    return c == 0 || c == 0x7f || (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v');
}

// ---------------------------------------------------------------------------
// ObjLineGate
// ---------------------------------------------------------------------------

ObjLineGate::ObjLineGate(char* begin, char* end) : pos_(begin), end_(end) {
    const auto byte = [&](size_t i) { return static_cast<unsigned char>(begin[i]); };
    if (end - begin >= 2 && ((byte(0) == 0xFE && byte(1) == 0xFF) || (byte(0) == 0xFF && byte(1) == 0xFE))) {
        error_line_ = 1;  // tinyobjloader would read every other byte as a NUL-cut line
        error_ = "UTF-16 text is not supported (save the file as UTF-8/ASCII)";
    }
}

ObjLineGate::int_type ObjLineGate::underflow() {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (!next_line()) return traits_type::eof();
    setg(served_, served_, pos_);
    return traits_type::to_int_type(*gptr());
}

void ObjLineGate::check_rest() {
    while (next_line()) {
    }
}

bool ObjLineGate::next_line() {
    if (error_line_ != 0 || pos_ == end_) return false;
    char* eol = pos_;
    while (eol != end_ && *eol != '\n' && *eol != '\r') ++eol;
    char* next = eol;
    if (next != end_) next += (*next == '\r' && next + 1 != end_ && next[1] == '\n') ? 2 : 1;
    ++line_no_;
    std::string why = check(std::string_view(pos_, size_t(eol - pos_)));
    if (!why.empty()) {
        error_line_ = line_no_;
        error_ = std::move(why);
        return false;
    }
    served_ = pos_;
    pos_ = next;
    return true;
}

std::string ObjLineGate::check(std::string_view line) {
    // tinyobjloader takes any bytes for text, and its C-string parsing ends a line at a NUL.
    for (unsigned char c : line) {
        if (is_binary_byte(c)) return "binary data, not a text OBJ file";
    }
    // The keyword first: most other lines need nothing more.
    size_t i = 0;
    while (i < line.size() && is_blank(line[i])) ++i;
    size_t k = i;
    while (k < line.size() && !is_blank(line[k])) ++k;
    const std::string_view key = line.substr(i, k - i);
    const bool numbers = key == "v" || key == "vt" || key == "vn";
    const bool corners = key == "f" || key == "l" || key == "p";
    if (!numbers && !corners) return {};
    // Its arguments, up to a trailing comment.
    tokens_.clear();
    for (i = k; i < line.size();) {
        while (i < line.size() && is_blank(line[i])) ++i;
        const size_t b = i;
        while (i < line.size() && !is_blank(line[i])) ++i;
        if (i == b) break;
        if (line[b] == '#') break;
        tokens_.push_back(line.substr(b, i - b));
    }
    return numbers ? check_numbers(key) : check_corners(key);
}

std::string ObjLineGate::check_numbers(std::string_view key) {
    const size_t need = key == "vt" ? 1 : 3;
    if (tokens_.size() < need) {
        return "truncated '" + std::string(key) + "' line (" + std::to_string(need) + " numbers expected)";
    }
    for (size_t i = 0; i < tokens_.size(); ++i) {
        const std::string_view tok = tokens_[i];
        double x = 0.0;
        if (!parse_double(tok, x)) return "bad number " + quote(tok);
        if (!std::isfinite(x)) return "non-finite number " + quote(tok);
        if (i < 3 && std::abs(x) > kMaxCoordinate) return "coordinate " + quote(tok) + " too large (limit 1e6)";
    }
    ++count_[key == "v" ? 0 : key == "vt" ? 1 : 2];
    return {};
}

std::string ObjLineGate::check_corners(std::string_view key) {
    static const char* const kind_name[3] = {"vertex", "texture coordinate", "normal"};
    const size_t n = tokens_.size(), need = key == "f" ? 3 : 1;
    if (n < need) {
        return std::string(key == "f" ? "face" : key == "l" ? "line" : "point") + " with " + std::to_string(n) +
               " vertices (at least " + std::to_string(need) + " needed)";
    }
    if (key == "f" && n > kMaxFaceCorners) {
        return "face with " + std::to_string(n) + " vertices (limit " + std::to_string(kMaxFaceCorners) + ")";
    }
    for (const std::string_view tok : tokens_) {
        // v, v/vt, v//vn or v/vt/vn
        std::string_view part[3];
        std::string_view rest = tok;
        int nparts = 0;
        while (true) {
            const size_t slash = rest.find('/');
            if (nparts == 3) return "bad face vertex " + quote(tok);
            part[nparts++] = rest.substr(0, slash);
            if (slash == std::string_view::npos) break;
            rest = rest.substr(slash + 1);
        }
        for (int k = 0; k < nparts; ++k) {
            if (part[k].empty() && k == 1 && nparts == 3) continue;  // v//vn
            long idx = 0;
            if (!parse_index(part[k], idx)) return "bad index in " + quote(tok);
            if (idx == 0) return std::string(kind_name[k]) + " index 0 (OBJ indices start at 1)";
            // Negative = relative to the elements read so far (−1 = the last one);
            // positive ones must refer to elements already read too.
            if (idx > 0 ? idx > count_[k] : idx < -count_[k]) {
                return std::string(kind_name[k]) + " index " + std::to_string(idx) + " out of range (" +
                       std::to_string(count_[k]) + " defined so far)";
            }
        }
    }
    return {};
}

}  // namespace lab::detail
