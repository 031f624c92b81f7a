// Time as the application layer sees it, so tests can run the throttling
// policy without waiting.
#ifndef SB_APP_CLOCK_H_
#define SB_APP_CLOCK_H_

#include <cstdint>

namespace sb::app {

class Clock {
 public:
  virtual ~Clock() = default;
  // Unix seconds.
  virtual int64_t Now() = 0;
  // Blocks the calling thread for `seconds` (> 0).
  virtual void Sleep(double seconds) = 0;
};

// The real clock. Thread-safe; never destroyed.
Clock& SystemClock();

}  // namespace sb::app

#endif  // SB_APP_CLOCK_H_
