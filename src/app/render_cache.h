// Rendered answers kept while a gym's data stays (issue 22, "Scale and
// speed"): the API dashboard's JSON and a wall page's route tables, keyed on
// (what, id, viewer) and valid for one stamp, the gym's data version (moved
// by every write of its routes, walls, circuits, members, targets, feedback,
// setters and ticks: store gym_versions) and the day (pages show ages in
// days). A write moves the version, so the next request renders again: the
// cache never serves an answer older than the last write.
//
//   std::optional<app::Stamp> s = *services.rendered.StampOf(gym);
//   if (s) if (auto hit = services.rendered.Find({"api_dashboard", gym, user}, *s)) ...
//   ... render text ...; if (s) services.rendered.Keep(key, *s, text);
//
// StampedLru is the one small least-recently-used helper behind it (and
// any other cache keyed on a stamp).
#ifndef SB_APP_RENDER_CACHE_H_
#define SB_APP_RENDER_CACHE_H_

#include <compare>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "app/clock.h"
#include "base/status.h"

namespace sb::store {
class Store;
class TickStore;
}  // namespace sb::store

namespace sb::app {

// What a kept value was made from: the gym's data version and the day.
struct Stamp {
  int64_t version = 0;
  int64_t day = 0;
  bool operator==(const Stamp&) const = default;
};

// A map from Key to an immutable Value valid for one Stamp, dropping the
// least recently used entry beyond `max_entries` entries or `max_bytes`
// bytes (each entry's size as Keep is told). Thread-safe; values are shared
// (a reader keeps its shared_ptr while another thread replaces the entry).
template <class Key, class Value>
class StampedLru {
 public:
  StampedLru(size_t max_entries, size_t max_bytes)
      : max_entries_(max_entries), max_bytes_(max_bytes) {}

  // The value kept for `key` at `stamp`; nullptr when none (or kept at
  // another stamp).
  std::shared_ptr<const Value> Find(const Key& key, const Stamp& stamp) {
    std::lock_guard<std::mutex> lock(mu_);
    auto it = index_.find(key);
    if (it == index_.end() || it->second->stamp != stamp) return nullptr;
    order_.splice(order_.begin(), order_, it->second);  // most recently used first
    return it->second->value;
  }

  // Keeps `value` (of `bytes` bytes) for `key` at `stamp`, replacing what
  // was kept, then drops the least recently used past the bounds. A value
  // larger than max_bytes is not kept.
  void Keep(const Key& key, const Stamp& stamp, std::shared_ptr<const Value> value,
            size_t bytes) {
    std::lock_guard<std::mutex> lock(mu_);
    if (auto it = index_.find(key); it != index_.end()) Erase(it);
    if (bytes > max_bytes_) return;
    order_.push_front(Entry{key, stamp, std::move(value), bytes});
    index_[key] = order_.begin();
    bytes_ += bytes;
    while (!order_.empty() && (order_.size() > max_entries_ || bytes_ > max_bytes_)) {
      Erase(index_.find(order_.back().key));
    }
  }

  // Entries kept now (tests).
  size_t size() {
    std::lock_guard<std::mutex> lock(mu_);
    return order_.size();
  }

 private:
  struct Entry {
    Key key;
    Stamp stamp;
    std::shared_ptr<const Value> value;
    size_t bytes = 0;
  };
  using Iter = typename std::list<Entry>::iterator;
  void Erase(typename std::map<Key, Iter>::iterator it) {
    bytes_ -= it->second->bytes;
    order_.erase(it->second);
    index_.erase(it);
  }

  const size_t max_entries_, max_bytes_;
  std::mutex mu_;
  std::list<Entry> order_;  // most recently used first
  std::map<Key, Iter> index_;
  size_t bytes_ = 0;
};

// What a rendered text is: its kind ("api_dashboard", "wall"), the id of
// the gym or wall, and the viewer's user id (0 when signed out): what a
// viewer sees differs by account.
struct RenderKey {
  std::string kind;
  int64_t id = 0;
  int64_t user = 0;
  auto operator<=>(const RenderKey&) const = default;
};

// The rendered texts of the web app's heaviest answers. Thread-safe. Does
// not own `store` or `clock`.
class RenderCache {
 public:
  // Texts kept: 20 head setters of a chain each on a dashboard and a wall
  // page, with room for their setters and climbers.
  static constexpr size_t kMaxEntries = 512;
  // Bytes kept: a chain gym's dashboard JSON is ~0.3 MB (500 routes), a
  // wall page's tables ~40 KB; 64 MiB holds every gym's and stays well
  // inside the server's memory bound.
  static constexpr size_t kMaxBytes = 64u << 20;

  RenderCache(store::Store* store, Clock* clock);

  // The stamp of gym `gym`'s data now (its data version, today's day);
  // nullopt when the store keeps no versions or has none for the gym (then
  // nothing is cached). Read it BEFORE reading what is rendered, so a write
  // during the render leaves the text under the older stamp. Errors: the
  // store's.
  Result<std::optional<Stamp>> StampOf(int64_t gym);
  // The text kept for `key` at `stamp` (nullptr when none).
  std::shared_ptr<const std::string> Find(const RenderKey& key, const Stamp& stamp);
  // Keeps `text` for `key` at `stamp` and returns it shared.
  std::shared_ptr<const std::string> Keep(const RenderKey& key, const Stamp& stamp,
                                          std::string text);

 private:
  store::TickStore* ticks_;
  Clock* clock_;
  StampedLru<RenderKey, std::string> texts_{kMaxEntries, kMaxBytes};
};

}  // namespace sb::app

#endif  // SB_APP_RENDER_CACHE_H_
