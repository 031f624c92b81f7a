// Landscape map files (landscape::DecodeMap). The harness puts the right
// checksum in the last 8 bytes so mutations reach the header and records.
// Errors name the file; a map that decodes encodes back to the same bytes,
// holds only values within the limits, and renders (slice, CSV and PNG for
// small grids) without error.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.h"
#include "landscape/map_file.h"
#include "landscape/pick.h"
#include "landscape/render.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  namespace ls = sb::landscape;
  std::string bytes =
      sb::fuzz::WithChecksum(std::string_view(reinterpret_cast<const char*>(data), size));
  auto m = ls::DecodeMap(bytes, "m.map");
  if (!m.ok()) {
    Check(m.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + m.status().message());
    Check(m.status().message().starts_with("m.map: "),
          "error names no file: " + m.status().message());
    return 0;
  }
  Check(ls::EncodeMap(*m) == bytes, "a decoded map does not encode to its bytes");
  Check(ls::ValidateScan(m->params, m->region).ok(), "decoded map outside the limits");
  auto slice = ls::ExtractSlice(*m, std::nullopt, std::nullopt);
  Check(slice.ok(), "slice of a valid map: " + slice.status().message());
  (void)ls::SliceCsv(*slice);
  if (m->region.grid <= 16) {
    auto png = ls::RenderPng(*slice, ls::Metric::kChange);
    Check(png.ok(), "render of a valid map: " + png.status().message());
  }
  ls::PickRequest req;
  req.effect = m->params.length / 2.0;
  req.count = 3;
  auto picked = ls::Pick(*m, req);
  Check(picked.ok(), "pick on a valid map: " + picked.status().message());
  return 0;
}
