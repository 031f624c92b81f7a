// The JSON bodies of the web API that carry variation parameters, decoded
// by the VaryParams JSON codec. Invalid JSON is the HTTP layer's to refuse;
// for any JSON value the decoder answers an error naming the field or
// parameters that validate and round-trip (encode -> decode -> equal
// encoding). It must never throw.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "fuzz/fuzz_util.h"
#include "chaos/variation.h"

namespace {

// The codec under test (chaos/variation.h), on JSON text.
sb::Result<sb::chaos::VaryParams> Decode(const nlohmann::json& j) {
  return sb::chaos::ParamsFromJson(j.dump());
}
nlohmann::json Encode(const sb::chaos::VaryParams& p) {
  return nlohmann::json::parse(sb::chaos::ParamsToJson(p));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  nlohmann::json j = nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return 0;
  auto p = Decode(j);
  if (!p.ok()) {
    Check(p.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + p.status().message());
    Check(!p.status().message().empty(), "empty error");
    return 0;
  }
  Check(p->Validate().ok(), "decoded parameters do not validate: " + p->Validate().message());
  nlohmann::json e = Encode(*p);
  auto back = Decode(e);
  Check(back.ok(), "encoded parameters do not decode: " + back.status().message());
  Check(Encode(*back).dump() == e.dump(), "encode -> decode -> encode changed the parameters");
  return 0;
}
