// Graph files (graph::GraphModel::Parse, docs/dance.md). The harness puts
// the right checksum line in place so mutations reach the content behind it
// (the file ends in "checksum <16 hex digits>\n"). Errors are kInvalidInput
// naming the file; a graph that loads serialises back to the same bytes and
// decodes what it encodes.
#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "base/hash.h"
#include "fuzz/fuzz_util.h"
#include "graph/graph.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using sb::fuzz::Check;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  // Replace a trailing checksum line with the right one.
  size_t at = bytes.rfind("checksum ");
  if (at != std::string::npos && (at == 0 || bytes[at - 1] == '\n')) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(sb::Fnv1a64(std::string_view(bytes).substr(0, at))));
    bytes = bytes.substr(0, at) + "checksum " + hex + "\n";
  }
  auto g = sb::graph::GraphModel::Parse(bytes, "g.sbg");
  if (!g.ok()) {
    Check(g.status().code() == sb::Status::Code::kInvalidInput,
          "not kInvalidInput: " + g.status().message());
    Check(g.status().message().starts_with("g.sbg"), "error names no file: " + g.status().message());
    return 0;
  }
  std::string again = g->Serialize();
  auto g2 = sb::graph::GraphModel::Parse(again, "g2.sbg");
  Check(g2.ok(), "a serialised graph does not parse: " + (g2.ok() ? "" : g2.status().message()));
  Check(g2->Serialize() == again, "serialise/parse is not a fixed point");
  return 0;
}
