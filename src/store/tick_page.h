// Test-only: the page of a gym's tick read (issue 34). TickStore::GymTicks
// reads a gym's ticks in pages of 10,000 by id (store/tick_sql.cc); tests set a
// small page to show that the pages join up. Kept out of store/tick_store.h,
// which most of the app includes.
#ifndef SB_STORE_TICK_PAGE_H_
#define SB_STORE_TICK_PAGE_H_

#include <cstdint>

namespace sb::store {

// Sets how many ticks TickStore::GymTicks reads per query (default 10,000; at
// least 1) for every store of this process, so that tests can show the pages
// join up (the same ticks in the same order, the same fit). Returns the
// previous value. Thread-safe (reads already under way keep theirs).
int64_t SetGymTickPageForTesting(int64_t page);

}  // namespace sb::store

#endif  // SB_STORE_TICK_PAGE_H_
