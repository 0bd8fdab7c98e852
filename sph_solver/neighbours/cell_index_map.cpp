#include "sph_solver/neighbours/cell_index_map.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace tankfsi::sph {

namespace {

constexpr std::size_t initial_capacity = 64;  // a power of two

// The finaliser of SplitMix64 (Steele, Lea & Flood 2014): every input bit affects
// every output bit, so neighbouring cells land in unrelated slots.
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

}  // namespace

void CellIndexMap::clear() {
  std::fill(values_.begin(), values_.end(), -1);
  size_ = 0;
}

std::size_t CellIndexMap::slot_of(const CellCoordinates& cell) const {
  std::uint64_t hash = 0;
  for (std::int64_t coordinate : cell) hash = mix(hash ^ static_cast<std::uint64_t>(coordinate));
  return static_cast<std::size_t>(hash) & (values_.size() - 1);
}

int CellIndexMap::find(const CellCoordinates& cell) const {
  if (values_.empty()) return -1;
  const std::size_t mask = values_.size() - 1;
  for (std::size_t slot = slot_of(cell);; slot = (slot + 1) & mask) {
    if (values_[slot] < 0) return -1;
    if (keys_[slot] == cell) return values_[slot];
  }
}

int CellIndexMap::find_or_insert(const CellCoordinates& cell, int index_if_absent) {
  // Keep the load factor at or below 1/2 so probe sequences stay short.
  if (2 * (size_ + 1) > values_.size()) grow();
  const std::size_t mask = values_.size() - 1;
  for (std::size_t slot = slot_of(cell);; slot = (slot + 1) & mask) {
    if (values_[slot] < 0) {
      keys_[slot] = cell;
      values_[slot] = index_if_absent;
      ++size_;
      return index_if_absent;
    }
    if (keys_[slot] == cell) return values_[slot];
  }
}

void CellIndexMap::grow() {
  std::vector<CellCoordinates> old_keys = std::move(keys_);
  std::vector<int> old_values = std::move(values_);
  const std::size_t capacity = std::max(initial_capacity, 2 * old_values.size());
  keys_.assign(capacity, CellCoordinates{});
  values_.assign(capacity, -1);
  size_ = 0;
  for (std::size_t slot = 0; slot < old_values.size(); ++slot) {
    if (old_values[slot] >= 0) find_or_insert(old_keys[slot], old_values[slot]);
  }
}

}  // namespace tankfsi::sph
