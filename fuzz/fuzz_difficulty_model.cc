// Difficulty model files (difficulty::ParseModel, docs/setting.md). The
// harness puts the right FNV-1a checksum in place when the file ends in a
// "checksum <hex>" line. Errors are kInvalidInput "d.sbd:line: ..."; a model
// that loads formats to text that loads to the same text.
#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "base/hash.h"
#include "difficulty/difficulty.h"
#include "fuzz/fuzz_util.h"

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
  auto m = sb::difficulty::ParseModel(bytes, "d.sbd");
  if (!m.ok()) {
    Check(m.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + m.status().message());
    Check(m.status().message().starts_with("d.sbd"), "error names no file: " + m.status().message());
    return 0;
  }
  std::string again = sb::difficulty::FormatModel(*m);
  auto m2 = sb::difficulty::ParseModel(again, "d2.sbd");
  Check(m2.ok(), "a formatted model does not parse: " + (m2.ok() ? "" : m2.status().message()));
  Check(sb::difficulty::FormatModel(*m2) == again, "format/parse is not a fixed point");
  return 0;
}
