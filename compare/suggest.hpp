#pragma once
// "Did you mean …?" for the command line: a misspelt command, backend or
// option value is answered with the nearest name, never silently replaced.
#include <string>
#include <string_view>
#include <vector>

namespace gacompare::compare {

// The optimal-string-alignment distance (Levenshtein's insertions, deletions
// and substitutions, plus a swap of two neighbouring characters as one edit:
// "comapre" is one edit from "compare"), bytewise.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate nearest `word`, when it is close enough to be what was meant:
// at most max(1, |word| / 3) edits away (so "cgaa" → "cga", "xyz" → nothing).
// The first of equally near candidates; "" when none is near.
std::string closest(std::string_view word, const std::vector<std::string>& candidates);

// "'cgaa' is not one of traditional, cga or bullet; did you mean 'cga'?" (the
// hint only when closest() finds one). `what` names the kind ("backend").
std::string not_one_of(std::string_view what, std::string_view word, const std::vector<std::string>& candidates);

}  // namespace gacompare::compare
