#include "app/render_cache.h"

#include "store/tick_store.h"

namespace sb::app {

RenderCache::RenderCache(store::Store* store, Clock* clock)
    : ticks_(store::TickStoreOf(store)), clock_(clock) {}

Result<std::optional<Stamp>> RenderCache::StampOf(int64_t gym) {
  if (!ticks_) return std::optional<Stamp>();
  SB_ASSIGN_OR_RETURN(store::TickVersion tv, ticks_->GymTickVersion(gym));
  if (tv.data <= 0) return std::optional<Stamp>();
  return std::optional<Stamp>(Stamp{tv.data, clock_->Now() / 86400});
}

std::shared_ptr<const std::string> RenderCache::Find(const RenderKey& key, const Stamp& stamp) {
  return texts_.Find(key, stamp);
}

std::shared_ptr<const std::string> RenderCache::Keep(const RenderKey& key, const Stamp& stamp,
                                                     std::string text) {
  const size_t bytes = text.size() + key.kind.size() + sizeof(RenderKey);
  auto shared = std::make_shared<const std::string>(std::move(text));
  texts_.Keep(key, stamp, shared, bytes);
  return shared;
}

}  // namespace sb::app
