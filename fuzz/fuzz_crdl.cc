// CRDL route text (sb::ParseCrdl): errors are located "f.crdl:line:col:";
// a parsed route (moves or none: issue 32) prints as CRDL that parses back to the same
// route, and printing is a fixed point.
#include <cstddef>
#include <cstdint>

#include "crdl/route.h"
#include "fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto r = sb::ParseCrdl(text, "f.crdl");
  if (!r.ok()) {
    sb::fuzz::CheckLocatedError(r.status(), "f.crdl", true);
    return 0;
  }
  std::string printed = sb::PrintCrdl(*r);
  auto again = sb::ParseCrdl(printed, "printed.crdl");
  Check(again.ok(), "printed route does not parse: " + again.status().message());
  Check(*again == *r, "print -> parse changed the route");
  Check(sb::PrintCrdl(*again) == printed, "print is not a fixed point");
  return 0;
}
