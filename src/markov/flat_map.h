// Internal: an open-addressing hash map from 64-bit keys to 32-bit values,
// used for context-trie edges. Not part of the public API.
#ifndef SB_MARKOV_FLAT_MAP_H_
#define SB_MARKOV_FLAT_MAP_H_

#include <cstdint>
#include <utility>
#include <vector>

namespace sb::markov::internal {

// Maps uint64 keys (never kEmpty) to uint32 values. Linear probing, power-of-two
// capacity, load factor <= 1/2. Not thread-safe for writes; concurrent Find()
// calls on an unchanging map are safe.
class FlatMap {
 public:
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  static constexpr uint32_t kNone = ~uint32_t{0};

  FlatMap() { Rehash(16); }

  // Returns the value for `key`, or kNone.
  uint32_t Find(uint64_t key) const { return FindIn(keys_.data(), values_.data(), mask_, key); }

  // Find over a raw table (keys/values of capacity mask + 1, at least one
  // free slot), e.g. one mapped from a model file.
  static uint32_t FindIn(const uint64_t* keys, const uint32_t* values, size_t mask, uint64_t key) {
    size_t i = SlotOf(key, mask);
    for (;;) {
      const uint64_t k = keys[i];
      if (k == key) return values[i];
      if (k == kEmpty) return kNone;
      i = (i + 1) & mask;
    }
  }
  size_t mask() const { return mask_; }

  // Returns a reference to the value for `key`, inserting `fresh` when absent;
  // `*inserted` tells which. The reference is valid until the next insertion.
  uint32_t& FindOrInsert(uint64_t key, uint32_t fresh, bool* inserted) {
    if ((size_ + 1) * 2 > keys_.size()) Rehash(keys_.size() * 2);
    size_t i = Slot(key);
    for (;;) {
      const uint64_t k = keys_[i];
      if (k == key) {
        *inserted = false;
        return values_[i];
      }
      if (k == kEmpty) {
        keys_[i] = key;
        values_[i] = fresh;
        ++size_;
        *inserted = true;
        return values_[i];
      }
      i = (i + 1) & mask_;
    }
  }

  size_t size() const { return size_; }
  size_t MemoryBytes() const { return keys_.capacity() * 12; }

  // The raw table (model files): keys (kEmpty = free slot) and values, one
  // per slot; the capacity is a power of two.
  const std::vector<uint64_t>& raw_keys() const { return keys_; }
  const std::vector<uint32_t>& raw_values() const { return values_; }
  // Takes over a raw table written by raw_keys()/raw_values(). Returns false
  // (leaving the map unchanged) unless the capacity is a power of two >= 16,
  // the arrays have equal sizes and at most half the slots are used, so
  // every probe ends at a free slot.
  bool Adopt(std::vector<uint64_t> keys, std::vector<uint32_t> values) {
    const size_t cap = keys.size();
    if (cap < 16 || (cap & (cap - 1)) != 0 || values.size() != cap) return false;
    size_t used = 0;
    for (uint64_t k : keys) used += k != kEmpty;
    if (used * 2 > cap) return false;
    keys_ = std::move(keys);
    values_ = std::move(values);
    mask_ = cap - 1;
    size_ = used;
    return true;
  }

  // Calls f(key, value) for every entry, in slot order.
  template <typename F>
  void ForEach(F&& f) const {
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != kEmpty) f(keys_[i], values_[i]);
  }

 private:
  static size_t SlotOf(uint64_t key, size_t mask) {
    uint64_t h = key * 0x9E3779B97F4A7C15ull;
    h ^= h >> 29;
    return static_cast<size_t>(h) & mask;
  }
  size_t Slot(uint64_t key) const { return SlotOf(key, mask_); }
  void Rehash(size_t cap) {
    std::vector<uint64_t> old_keys;
    std::vector<uint32_t> old_values;
    old_keys.swap(keys_);
    old_values.swap(values_);
    keys_.assign(cap, kEmpty);
    values_.assign(cap, 0);
    mask_ = cap - 1;
    size_ = 0;
    for (size_t i = 0; i < old_keys.size(); ++i) {
      if (old_keys[i] == kEmpty) continue;
      size_t j = Slot(old_keys[i]);
      while (keys_[j] != kEmpty) j = (j + 1) & mask_;
      keys_[j] = old_keys[i];
      values_[j] = old_values[i];
      ++size_;
    }
  }

  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t mask_ = 0;
  size_t size_ = 0;
};

// Tag of the constructors that build a model from a model file's state.
struct LoadOnly {};
inline constexpr LoadOnly kLoadOnly{};

// Key of the trie edge from `node` by symbol `sym`.
inline uint64_t EdgeKey(uint32_t node, int32_t sym) {
  return (uint64_t{node} << 32) | static_cast<uint32_t>(sym);
}

}  // namespace sb::markov::internal

#endif  // SB_MARKOV_FLAT_MAP_H_
