// Landscape map files: a scan's parameters, region and per-IC results in one
// binary file (format: docs/formats.md, "Landscape map files").
#ifndef SB_LANDSCAPE_MAP_FILE_H_
#define SB_LANDSCAPE_MAP_FILE_H_

#include <string>
#include <string_view>

#include "base/status.h"
#include "landscape/landscape.h"

namespace sb::landscape {

// The file's first 8 bytes.
inline constexpr char kMapMagic[8] = {'S', 'B', 'L', 'M', 'A', 'P', '1', '\n'};
inline constexpr uint32_t kMapVersion = 1;
// Bytes before the effect array.
inline constexpr size_t kMapHeaderSize = 144;

// Serialises a map (header, effect array, displacement array, checksum).
// Deterministic: equal maps give equal bytes. Pure; thread-safe.
std::string EncodeMap(const LandscapeMap& map);

// Parses EncodeMap's output. `name` (usually the path) prefixes messages.
// Errors (kInvalidInput): wrong magic or version, truncated or oversized
// data, checksum mismatch, or a header field out of range — the message names
// the field and its byte offset, e.g. "m.map: offset 84 (length): 0 is out of
// range". Pure; thread-safe.
Result<LandscapeMap> DecodeMap(std::string_view data, std::string_view name);

// EncodeMap + sb::WriteFileAtomic (never leaves a half-written file).
// Errors: kIoError.
Status WriteMapFile(const std::string& path, const LandscapeMap& map);

// sb::ReadFile + DecodeMap. Errors: kNotFound/kIoError, or DecodeMap's.
Result<LandscapeMap> ReadMapFile(const std::string& path);

}  // namespace sb::landscape

#endif  // SB_LANDSCAPE_MAP_FILE_H_
