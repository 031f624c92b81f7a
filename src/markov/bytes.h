// Internal: little-endian byte writing and bounds-checked reading for model
// files. Not part of the public API.
#ifndef SB_MARKOV_BYTES_H_
#define SB_MARKOV_BYTES_H_

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace sb::markov::internal {

inline void PutU32(std::string* out, uint32_t v) {
  char b[4];
  for (int i = 0; i < 4; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xff);
  out->append(b, 4);
}
inline void PutU64(std::string* out, uint64_t v) {
  char b[8];
  for (int i = 0; i < 8; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xff);
  out->append(b, 8);
}
inline void PutF64(std::string* out, double v) {
  uint64_t bits;
  std::memcpy(&bits, &v, 8);
  PutU64(out, bits);
}
// Appends an array of 32/64-bit integers, little-endian.
template <typename T>
void PutArray(std::string* out, const std::vector<T>& v) {
  static_assert(sizeof(T) == 4 || sizeof(T) == 8);
  if constexpr (std::endian::native == std::endian::little) {
    out->append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  } else {
    for (T x : v) {
      if constexpr (sizeof(T) == 4)
        PutU32(out, static_cast<uint32_t>(x));
      else
        PutU64(out, static_cast<uint64_t>(x));
    }
  }
}

// Reads from a byte string; every read fails (returns false) past the end.
class ByteReader {
 public:
  explicit ByteReader(std::string_view b) : b_(b) {}
  bool U32(uint32_t* v) {
    if (b_.size() - pos_ < 4) return false;
    *v = 0;
    for (int i = 0; i < 4; ++i) *v |= uint32_t{static_cast<unsigned char>(b_[pos_ + i])} << (8 * i);
    pos_ += 4;
    return true;
  }
  bool U64(uint64_t* v) {
    if (b_.size() - pos_ < 8) return false;
    *v = 0;
    for (int i = 0; i < 8; ++i) *v |= uint64_t{static_cast<unsigned char>(b_[pos_ + i])} << (8 * i);
    pos_ += 8;
    return true;
  }
  bool F64(double* v) {
    uint64_t bits = 0;
    if (!U64(&bits)) return false;
    std::memcpy(v, &bits, 8);
    return true;
  }
  bool Bytes(size_t n, std::string_view* s) {
    if (b_.size() - pos_ < n) return false;
    *s = b_.substr(pos_, n);
    pos_ += n;
    return true;
  }
  // Reads n integers of type T into *v (resized).
  template <typename T>
  bool Array(uint64_t n, std::vector<T>* v) {
    static_assert(sizeof(T) == 4 || sizeof(T) == 8);
    if (n > (b_.size() - pos_) / sizeof(T)) return false;
    v->resize(n);
    if constexpr (std::endian::native == std::endian::little) {
      // memcpy's pointers must not be null, even for 0 bytes (an empty
      // vector's data() may be).
      if (n > 0) std::memcpy(v->data(), b_.data() + pos_, n * sizeof(T));
      pos_ += n * sizeof(T);
    } else {
      for (uint64_t i = 0; i < n; ++i) {
        if constexpr (sizeof(T) == 4) {
          uint32_t x;
          U32(&x);
          (*v)[i] = static_cast<T>(x);
        } else {
          uint64_t x;
          U64(&x);
          (*v)[i] = static_cast<T>(x);
        }
      }
    }
    return true;
  }
  size_t remaining() const { return b_.size() - pos_; }
  size_t pos() const { return pos_; }

 private:
  std::string_view b_;
  size_t pos_ = 0;
};

}  // namespace sb::markov::internal

#endif  // SB_MARKOV_BYTES_H_
