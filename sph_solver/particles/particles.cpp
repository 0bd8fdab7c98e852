#include "sph_solver/particles/particles.hpp"

namespace tankfsi::sph {
namespace {

template <class T>
void reorder_field(std::vector<T>& field, const std::vector<int>& order) {
  std::vector<T> sorted;
  sorted.reserve(order.size());
  for (const int k : order) sorted.push_back(field[static_cast<std::size_t>(k)]);
  field.swap(sorted);
}

}  // namespace

void Particles::reorder(const std::vector<int>& order) {
  reorder_field(id, order);
  reorder_field(position, order);
  reorder_field(velocity, order);
  reorder_field(mass, order);
  reorder_field(pressure, order);
}

}  // namespace tankfsi::sph
