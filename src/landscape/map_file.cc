#include "landscape/map_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "base/files.h"
#include "base/hash.h"

namespace sb::landscape {

namespace {

class Writer {
 public:
  void U16(uint16_t v) { Le(v, 2); }
  void U32(uint32_t v) { Le(v, 4); }
  void U64(uint64_t v) { Le(v, 8); }
  void F64(double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, 8);
    Le(bits, 8);
  }
  void Bytes(const char* p, size_t n) { out_.append(p, n); }
  std::string& out() { return out_; }

 private:
  void Le(uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  std::string out_;
};

uint64_t ReadLe(std::string_view d, size_t off, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) {
    v |= static_cast<uint64_t>(static_cast<unsigned char>(d[off + i])) << (8 * i);
  }
  return v;
}

double ReadF64(std::string_view d, size_t off) {
  uint64_t bits = ReadLe(d, off, 8);
  double v;
  std::memcpy(&v, &bits, 8);
  return v;
}

}  // namespace

std::string EncodeMap(const LandscapeMap& map) {
  Writer w;
  const ScanParams& p = map.params;
  const Region& r = map.region;
  w.Bytes(kMapMagic, 8);                                       // 0
  w.U32(kMapVersion);                                          // 8
  w.U32(static_cast<uint32_t>(kMapHeaderSize));                // 12
  w.U32(p.system.kind == chaos::SystemKind::kLorenz ? 0 : 1);  // 16
  w.U32(p.integrator == chaos::IntegratorKind::kRk4 ? 0 : 1);  // 20
  for (double v : p.system.params) w.F64(v);                   // 24
  w.F64(p.step);                                               // 48
  for (double v : p.ref_ic) w.F64(v);                          // 56
  w.U32(static_cast<uint32_t>(p.skip));                        // 80
  w.U32(static_cast<uint32_t>(p.length));                      // 84
  w.U32(p.mask);                                               // 88
  w.U32(static_cast<uint32_t>(r.plane));                       // 92
  w.U32(static_cast<uint32_t>(r.grid));                        // 96
  w.U32(0);                                                    // 100
  w.F64(r.spacing);                                            // 104
  for (double v : r.center) w.F64(v);                          // 112
  w.U64(map.size());                                           // 136
  w.out().reserve(kMapHeaderSize + map.size() * 6 + 8);
  for (uint16_t e : map.effect) w.U16(e);  // 144
  for (uint32_t d : map.displacement) w.U32(d);
  uint64_t sum = Fnv1a64(w.out());
  w.U64(sum);
  return std::move(w.out());
}

namespace {

// Checks the magic and the header (the first kMapHeaderSize bytes of `d`,
// which must be there) into m->params and m->region; *total receives the
// size of the whole file the header implies. Errors name `n` and, for
// fields, the byte offset.
Status DecodeHeader(std::string_view d, const std::string& n, LandscapeMap* m, uint64_t* total) {
  auto bad = [&](size_t off, const char* field, const std::string& why) {
    return Status::InvalidInput(n + ": offset " + std::to_string(off) + " (" + field + "): " + why);
  };
  if (d.size() < 8 || std::memcmp(d.data(), kMapMagic, 8) != 0) {
    return Status::InvalidInput(n + ": not a strangebeta landscape map (bad magic)");
  }
  if (d.size() < kMapHeaderSize) {
    return Status::InvalidInput(n + ": truncated: " + std::to_string(d.size()) +
                                " bytes, the header alone is " + std::to_string(kMapHeaderSize));
  }
  uint32_t version = static_cast<uint32_t>(ReadLe(d, 8, 4));
  if (version != kMapVersion) {
    return bad(8, "version",
               "unsupported version " + std::to_string(version) + " (expected " +
                   std::to_string(kMapVersion) + ")");
  }
  uint32_t header_size = static_cast<uint32_t>(ReadLe(d, 12, 4));
  if (header_size != kMapHeaderSize) {
    return bad(12, "header_size",
               std::to_string(header_size) + " is not " + std::to_string(kMapHeaderSize));
  }
  ScanParams& p = m->params;
  Region& r = m->region;
  uint32_t system = static_cast<uint32_t>(ReadLe(d, 16, 4));
  if (system > 1) return bad(16, "system", std::to_string(system) + " is not 0 or 1");
  p.system.kind = system == 0 ? chaos::SystemKind::kLorenz : chaos::SystemKind::kRossler;
  uint32_t integ = static_cast<uint32_t>(ReadLe(d, 20, 4));
  if (integ > 1) return bad(20, "integrator", std::to_string(integ) + " is not 0 or 1");
  p.integrator = integ == 0 ? chaos::IntegratorKind::kRk4 : chaos::IntegratorKind::kRkf45;
  for (int i = 0; i < 3; ++i) p.system.params[i] = ReadF64(d, 24 + 8 * i);
  p.step = ReadF64(d, 48);
  for (int i = 0; i < 3; ++i) p.ref_ic[i] = ReadF64(d, 56 + 8 * i);
  uint32_t skip = static_cast<uint32_t>(ReadLe(d, 80, 4));
  if (skip > static_cast<uint32_t>(chaos::kMaxSkip)) {
    return bad(80, "skip", std::to_string(skip) + " is out of range");
  }
  p.skip = static_cast<int>(skip);
  uint32_t length = static_cast<uint32_t>(ReadLe(d, 84, 4));
  if (length < 1 || length > static_cast<uint32_t>(kMaxLength)) {
    return bad(84, "length", std::to_string(length) + " is out of range");
  }
  p.length = static_cast<int>(length);
  p.mask = static_cast<uint32_t>(ReadLe(d, 88, 4));
  if (p.mask < 1 || p.mask > 7) return bad(88, "mask", std::to_string(p.mask) + " is not 1..7");
  uint32_t plane = static_cast<uint32_t>(ReadLe(d, 92, 4));
  if (plane > 3) return bad(92, "plane", std::to_string(plane) + " is not 0..3");
  r.plane = static_cast<Plane>(plane);
  uint32_t grid = static_cast<uint32_t>(ReadLe(d, 96, 4));
  if (grid < 1 || grid > static_cast<uint32_t>(kMaxGrid)) {
    return bad(96, "grid", std::to_string(grid) + " is not 1.." + std::to_string(kMaxGrid));
  }
  r.grid = static_cast<int>(grid);
  uint32_t reserved = static_cast<uint32_t>(ReadLe(d, 100, 4));
  if (reserved != 0) return bad(100, "reserved", std::to_string(reserved) + " is not 0");
  r.spacing = ReadF64(d, 104);
  for (int i = 0; i < 3; ++i) r.center[i] = ReadF64(d, 112 + 8 * i);
  // The same ranges as a scan: finite numbers, coordinates and spacing
  // within the limits (so rendering and picking stay exact and bounded).
  Status vs = ValidateScan(p, r);
  if (!vs.ok()) return Status::InvalidInput(n + ": header: " + vs.message());
  uint64_t count = ReadLe(d, 136, 8);
  if (count != r.size()) {
    return bad(136, "count",
               std::to_string(count) + " does not match the region's " + std::to_string(r.size()) +
                   " ICs");
  }
  *total = kMapHeaderSize + count * 6 + 8;
  return Status::Ok();
}

}  // namespace

Result<LandscapeMap> DecodeMap(std::string_view d, std::string_view name) {
  const std::string n(name);
  auto bad = [&](size_t off, const char* field, const std::string& why) {
    return Status::InvalidInput(n + ": offset " + std::to_string(off) + " (" + field + "): " + why);
  };
  LandscapeMap m;
  uint64_t want = 0;
  SB_RETURN_IF_ERROR(DecodeHeader(d, n, &m, &want));
  const uint64_t count = m.region.size();
  const ScanParams& p = m.params;
  if (d.size() != want) {
    return Status::InvalidInput(n + ": " + (d.size() < want ? "truncated" : "trailing data") +
                                ": " + std::to_string(d.size()) + " bytes, expected " +
                                std::to_string(want));
  }
  uint64_t stored = ReadLe(d, want - 8, 8);
  if (stored != Fnv1a64(d.substr(0, want - 8))) {
    return Status::InvalidInput(n + ": checksum mismatch: the file is corrupt");
  }
  m.effect.resize(count);
  m.displacement.resize(count);
  size_t off = kMapHeaderSize;
  for (uint64_t i = 0; i < count; ++i, off += 2) {
    m.effect[i] = static_cast<uint16_t>(ReadLe(d, off, 2));
  }
  for (uint64_t i = 0; i < count; ++i, off += 4) {
    m.displacement[i] = static_cast<uint32_t>(ReadLe(d, off, 4));
  }
  const uint64_t nmax = static_cast<uint64_t>(p.length);
  for (uint64_t i = 0; i < count; ++i) {
    if (m.effect[i] > nmax || (m.effect[i] == 0) != (m.displacement[i] == 0) ||
        m.displacement[i] > m.effect[i] * (nmax - 1)) {
      return bad(kMapHeaderSize + 2 * i, "effect",
                 "IC " + std::to_string(i) + " has impossible effect " +
                     std::to_string(m.effect[i]) + " / displacement " +
                     std::to_string(m.displacement[i]));
    }
  }
  return m;
}

Status WriteMapFile(const std::string& path, const LandscapeMap& map) {
  return WriteFileAtomic(path, EncodeMap(map));
}

Result<LandscapeMap> ReadMapFile(const std::string& path) {
  // The header first: the file's size follows from it, so a damaged or
  // endless file is refused before reading (or allocating) more.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Status::IoError(path + ": is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (errno == ENOENT) return Status::NotFound(path + ": no such file");
    return Status::IoError(path + ": " + std::strerror(errno));
  }
  std::string data(kMapHeaderSize, '\0');
  in.read(data.data(), static_cast<std::streamsize>(data.size()));
  data.resize(static_cast<size_t>(in.gcount()));
  if (in.bad()) return Status::IoError(path + ": read error");
  if (data.size() == kMapHeaderSize) {
    uint64_t want = 0;
    LandscapeMap header;
    SB_RETURN_IF_ERROR(DecodeHeader(data, path, &header, &want));
    // In chunks, so memory grows with what the file really holds; one
    // byte more than the header says shows trailing data.
    char buf[1 << 16];
    while (in && data.size() <= want) {
      in.read(buf,
              static_cast<std::streamsize>(std::min<uint64_t>(sizeof buf, want + 1 - data.size())));
      data.append(buf, static_cast<size_t>(in.gcount()));
    }
    if (in.bad()) return Status::IoError(path + ": read error");
  }
  return DecodeMap(data, path);
}

}  // namespace sb::landscape
