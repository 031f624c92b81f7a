// Markov model files (markov::TokenModel::Parse). The harness puts the right
// checksum in the last 8 bytes so mutations reach the content behind it.
// Errors name the file; a model that loads serialises back to the same
// bytes (a format-1 file: to format 2, a fixed point), has a consistent vocabulary of valid UTF-8 tokens (the file format
// says UTF-8; other modules print them as JSON), and encodes/decodes every
// token.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.h"
#include "markov/token_model.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  std::string bytes =
      sb::fuzz::WithChecksum(std::string_view(reinterpret_cast<const char*>(data), size));
  auto m = sb::markov::TokenModel::Parse(bytes, "m.sbm");
  if (!m.ok()) {
    Check(m.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + m.status().message());
    Check(m.status().message().starts_with("m.sbm"),
          "error names no file: " + m.status().message());
    return 0;
  }
  // A model in the current format serialises to its bytes; an older one
  // (format 1) to the current format, which then is a fixed point.
  const std::string out = m->Serialize();
  if (out.compare(0, 12, bytes, 0, 12) == 0) {
    Check(out == bytes, "a loaded model does not serialise to its bytes");
  } else {
    auto again = sb::markov::TokenModel::Parse(out, "m.sbm");
    Check(again.ok(), "an upgraded model does not load: " + again.status().message());
    Check(again->Serialize() == out, "an upgraded model does not serialise to its bytes");
  }
  if (m->has_vocabulary()) {
    const auto& tokens = m->vocabulary().tokens();
    for (size_t i = 0; i < tokens.size(); ++i) {
      Check(sb::fuzz::ValidUtf8(tokens[i]), "vocabulary token is not UTF-8");
      Check(m->vocabulary().Id(tokens[i]) == static_cast<int32_t>(i), "token id mismatch");
    }
    auto ids = m->Encode(tokens);
    Check(ids.ok(), "vocabulary does not encode");
    for (size_t i = 0; i < tokens.size(); ++i) Check(m->Decode((*ids)[i]) == tokens[i], "decode");
  }
  for (const auto& [k, v] : m->metadata()) {
    Check(sb::fuzz::ValidUtf8(k) && sb::fuzz::ValidUtf8(v), "metadata is not UTF-8");
  }
  return 0;
}
