// Grade model files (grades::GradeEstimator::Parse, docs/grades.md). The
// harness puts the right FNV-1a checksum in place when the file ends in a
// "checksum <hex>" line. Errors are kInvalidInput naming the file; a model
// that loads serialises to bytes that load to the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "base/hash.h"
#include "fuzz/fuzz_util.h"
#include "grades/estimator.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  size_t at = bytes.rfind("checksum ");
  if (at != std::string::npos && (at == 0 || bytes[at - 1] == '\n')) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(sb::Fnv1a64(std::string_view(bytes).substr(0, at))));
    bytes = bytes.substr(0, at) + "checksum " + hex + "\n";
  }
  auto m = sb::grades::GradeEstimator::Parse(bytes, "m.sbg");
  if (!m.ok()) {
    Check(m.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + m.status().message());
    Check(m.status().message().starts_with("m.sbg"), "error names no file: " + m.status().message());
    return 0;
  }
  std::string again = m->Serialize();
  auto m2 = sb::grades::GradeEstimator::Parse(again, "m2.sbg");
  Check(m2.ok(), "a serialised model does not parse: " + (m2.ok() ? "" : m2.status().message()));
  Check(m2->Serialize() == again, "serialise/parse is not a fixed point");
  return 0;
}
