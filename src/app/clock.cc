#include "app/clock.h"

#include <chrono>
#include <ctime>
#include <thread>

namespace sb::app {

namespace {
class RealClock final : public Clock {
 public:
  int64_t Now() override { return static_cast<int64_t>(std::time(nullptr)); }
  void Sleep(double seconds) override {
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  }
};
}  // namespace

Clock& SystemClock() {
  static RealClock* clock = new RealClock();  // never destroyed: used until exit
  return *clock;
}

}  // namespace sb::app
