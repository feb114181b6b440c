// The glyph coverage cache: a hash map into an LRU list, bounded in bytes.
#include "vraster_text/render.hpp"

namespace vraster::text {
namespace {

inline std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  return h;
}

}  // namespace

std::size_t GlyphCache::KeyHash::operator()(const Key& k) const {
  std::uint64_t h = mix(k.font, k.glyph);
  h = mix(h, k.phase);
  h = mix(h, k.size_x_bits);
  h = mix(h, k.size_y_bits);
  h = mix(h, k.options);
  return static_cast<std::size_t>(h);
}

const GlyphMask* GlyphCache::find(const Key& key) {
  auto it = index_.find(key);
  if (it == index_.end()) {
    ++stats_.misses;
    return nullptr;
  }
  ++stats_.hits;
  if (it->second != lru_.begin()) lru_.splice(lru_.begin(), lru_, it->second);
  return &it->second->mask;
}

const GlyphMask* GlyphCache::insert(const Key& key, GlyphMask mask) {
  const std::size_t bytes = mask.bytes();
  if (bytes > max_bytes_ / 4) return nullptr;
  auto existing = index_.find(key);
  if (existing != index_.end()) {
    stats_.bytes -= existing->second->mask.bytes();
    lru_.erase(existing->second);
    index_.erase(existing);
  }
  evict_to(max_bytes_ - bytes);
  lru_.push_front({key, std::move(mask)});
  index_.emplace(key, lru_.begin());
  stats_.bytes += bytes;
  stats_.entries = index_.size();
  return &lru_.front().mask;
}

void GlyphCache::evict_to(std::size_t budget) {
  while (stats_.bytes > budget && !lru_.empty()) {
    const Entry& last = lru_.back();
    stats_.bytes -= last.mask.bytes();
    index_.erase(last.key);
    lru_.pop_back();
    ++stats_.evictions;
  }
  stats_.entries = index_.size();
}

void GlyphCache::clear() {
  lru_.clear();
  index_.clear();
  stats_.bytes = 0;
  stats_.entries = 0;
}

void GlyphCache::set_max_bytes(std::size_t max_bytes) {
  max_bytes_ = max_bytes;
  evict_to(max_bytes_);
}

}  // namespace vraster::text
