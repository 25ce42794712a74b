// "Did you mean" (compare/suggest.hpp): the distance against a brute-force
// recursion written from its definition, and the suggestions the command line
// makes from it.
#include "compare/suggest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>

using namespace gacompare::compare;

namespace {

// The optimal-string-alignment distance straight from its recurrence, on
// suffixes, exponential and obviously right: delete, insert, substitute (or
// match), or swap the next two characters.
std::size_t brute(const std::string& a, const std::string& b) {
  if (a.empty()) return b.size();
  if (b.empty()) return a.size();
  std::size_t best = std::min({brute(a.substr(1), b) + 1, brute(a, b.substr(1)) + 1,
                               brute(a.substr(1), b.substr(1)) + (a[0] == b[0] ? 0 : 1)});
  if (a.size() > 1 && b.size() > 1 && a[0] == b[1] && a[1] == b[0]) best = std::min(best, brute(a.substr(2), b.substr(2)) + 1);
  return best;
}

}  // namespace

TEST(EditDistance, KnownValues) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // Levenshtein's example: k→s, e→i, +g
  EXPECT_EQ(edit_distance("comapre", "compare"), 1u); // one swap
  EXPECT_EQ(edit_distance("", "cga"), 3u);
  EXPECT_EQ(edit_distance("cga", "cga"), 0u);
  EXPECT_EQ(edit_distance("ca", "abc"), 3u);  // OSA, not Damerau: no edit of a swapped pair
}

TEST(EditDistance, MatchesTheRecurrenceOnRandomWords) {
  // 2,000 pairs of words of up to 6 letters over {a, b, c}: small alphabets
  // make swaps and repeats common, where a dynamic programme goes wrong.
  std::mt19937 g(3);
  std::uniform_int_distribution<int> length(0, 6), letter(0, 2);
  for (int k = 0; k < 2000; ++k) {
    std::string a, b;
    for (int i = length(g); i > 0; --i) a += static_cast<char>('a' + letter(g));
    for (int i = length(g); i > 0; --i) b += static_cast<char>('a' + letter(g));
    ASSERT_EQ(edit_distance(a, b), brute(a, b)) << "'" << a << "' '" << b << "'";
    ASSERT_EQ(edit_distance(a, b), edit_distance(b, a));
  }
}

TEST(Closest, SuggestsOnlyWhatIsNear) {
  const std::vector<std::string> backends = {"traditional", "cga", "bullet"};
  EXPECT_EQ(closest("cgaa", backends), "cga");
  EXPECT_EQ(closest("tradtional", backends), "traditional");
  EXPECT_EQ(closest("bulet", backends), "bullet");
  EXPECT_EQ(closest("xyz", backends), "");          // 3 edits from cga: not a slip
  EXPECT_EQ(closest("quaternions", backends), "");
  EXPECT_EQ(not_one_of("backend", "cgaa", backends),
            "'cgaa' is not a backend (traditional, cga or bullet); did you mean 'cga'?");
  EXPECT_EQ(not_one_of("backend", "xyz", backends), "'xyz' is not a backend (traditional, cga or bullet)");
}
