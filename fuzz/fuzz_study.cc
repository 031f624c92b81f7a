// Study instruments (studies::ParseInstrument, JSON) and responses CSV
// (studies::ParseResponsesCsv against the built-in "pilot" instrument),
// docs/studies.md. The first input byte picks the format. Errors are
// kInvalidInput naming the file; a parsed instrument passes
// ValidateInstrument.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.h"
#include "studies/instrument.h"
#include "studies/responses.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  if (size == 0) return 0;
  std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] & 1) {
    auto i = sb::studies::ParseInstrument(text, "i.json");
    if (!i.ok()) {
      Check(i.status().code() == sb::Status::Code::kInvalidInput,
            "not kInvalidInput: " + i.status().message());
      Check(i.status().message().starts_with("i.json"),
            "error names no file: " + i.status().message());
      return 0;
    }
    Check(sb::studies::ValidateInstrument(*i, "i.json").ok(), "a parsed instrument is invalid");
    return 0;
  }
  static const auto* pilot = new sb::studies::Instrument(*sb::studies::LoadInstrument("pilot"));
  auto r = sb::studies::ParseResponsesCsv(text, "r.csv", *pilot);
  if (!r.ok()) {
    Check(r.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + r.status().message());
    Check(r.status().message().starts_with("r.csv"), "error names no file: " + r.status().message());
  }
  return 0;
}
