// text_match.h — "did you mean …?" for option names and scene keys.
#pragma once

#include <string>
#include <vector>

namespace lab {

std::string to_lower(std::string s);

// Edit distance, ignoring case: how many single-letter edits (insert, delete,
// replace, swap two neighbours) turn a into b. "postion" → "position" is 1.
size_t edit_distance(const std::string& a, const std::string& b);

// The candidate `word` is probably a typo of, or "" if none is close: at most
// `max_distance` edits away (the nearest wins; earlier candidates win ties).
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates, size_t max_distance);

}  // namespace lab
