// "Did you mean ...?" for mistyped verbs, options and enumerated values: the valid name closest
// to what was typed, as git and cargo suggest them.
#pragma once
#include <string>
#include <vector>

namespace bounce::app {

// Edit distance with adjacent transpositions (optimal string alignment; Damerau 1964): the
// fewest insertions, deletions, substitutions and swaps of neighbours turning `a` into `b`.
size_t editDistance(const std::string& a, const std::string& b);

// The candidate closest to `typed`, or "" when none is close: within an edit distance of a
// third of the candidate's length (at least 2, so "rendr" finds "render"), or the only
// candidate that `typed` (3 characters or more) begins.
std::string closestName(const std::string& typed, const std::vector<std::string>& candidates);

// " (did you mean X?)" for the closest candidate, or "" when none is close.
std::string didYouMean(const std::string& typed, const std::vector<std::string>& candidates);

// "a, b, c": the candidates joined for a message.
std::string joinNames(const std::vector<std::string>& names);

// Splits "a, b, c" (the form the library's *Names() functions return) into names.
std::vector<std::string> splitNames(const std::string& commaSeparated);

}  // namespace bounce::app
