// The waits of kept contacts refused in a row (core/collision/kept_contacts.hpp
// refuse): none within the patience, then 2^k − 1 detections after the
// patience's k-th further refusal, at most 2^kKeepBackOff − 1, written out
// here as the schedule the header states.
#include "core/collision/kept_contacts.hpp"

#include <gtest/gtest.h>

namespace gacompare::collision {
namespace {

TEST(KeptContacts, RefusalsInARowWaitOnlyPastThePatienceAndAtMostThirtyOne) {
  KeptState k;
  k.valid = true;
  const int waits[] = {1, 3, 7, 15, 31, 31, 31};
  for (int r = 1; r <= kKeepPatience + 7; ++r) {
    const bool keep_now = refuse(k);
    const int want = r <= kKeepPatience ? 0 : waits[r - kKeepPatience - 1];
    EXPECT_EQ(k.wait, want) << "refusal " << r;
    EXPECT_EQ(keep_now, want == 0) << "refusal " << r;
    k.wait = 0;  // as the narrowphase leaves it once the wait has run out
  }
  EXPECT_EQ(kKeepPatience, 16);
  EXPECT_EQ(kKeepBackOff, 5);
}

}  // namespace
}  // namespace gacompare::collision
