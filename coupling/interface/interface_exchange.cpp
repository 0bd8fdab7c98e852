#include "coupling/interface/interface_exchange.hpp"

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace tankfsi::coupling {

namespace {

template <typename T>
MPI_Datatype mpi_type();
template <>
MPI_Datatype mpi_type<double>() { return MPI_DOUBLE; }
template <>
MPI_Datatype mpi_type<std::int64_t>() { return MPI_INT64_T; }

// All ranks' vectors concatenated in rank order, on every rank.
template <typename T>
std::vector<T> all_gather(MPI_Comm comm, const std::vector<T>& mine) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<int> offsets(static_cast<std::size_t>(size), 0);
  std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
  std::vector<T> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(mine.data(), count, mpi_type<T>(), all.data(), counts.data(), offsets.data(), mpi_type<T>(), comm);
  return all;
}

}  // namespace

// ---- structure side --------------------------------------------------------

InterfaceExchange::InterfaceExchange(PartnerLink& link, const std::vector<std::int64_t>& ids,
                                     const std::vector<double>& coordinates,
                                     const std::vector<std::array<std::int64_t, 3>>& triangles)
    : link_(link) {
  if (coordinates.size() != 3 * ids.size())
    throw CouplingError("set_interface: " + std::to_string(coordinates.size()) + " coordinates for " +
                        std::to_string(ids.size()) + " vertices (3 per vertex expected)");
  {
    std::vector<std::int64_t> sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    const auto twin = std::adjacent_find(sorted.begin(), sorted.end());
    if (twin != sorted.end())
      throw CouplingError("set_interface: vertex id " + std::to_string(*twin) + " declared twice on one rank");
  }
  mesh_.ids = ids;
  mesh_.coordinates = coordinates;
  part_size_ = 3 * ids.size();
  unsigned long long declared = ids.size();
  MPI_Allreduce(MPI_IN_PLACE, &declared, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, link_.local());
  global_vertices_ = static_cast<std::size_t>(declared);

  // The mesh goes to fluid rank (own rank mod fluid ranks); the fluid ranks
  // share it among themselves.
  const int target = link_.rank() % link_.partner_size();
  std::vector<std::int64_t> sizes{static_cast<std::int64_t>(ids.size()), static_cast<std::int64_t>(triangles.size())};
  std::vector<std::int64_t> flat_triangles;
  flat_triangles.reserve(3 * triangles.size());
  for (const auto& t : triangles) flat_triangles.insert(flat_triangles.end(), t.begin(), t.end());
  std::vector<MPI_Request> requests(4);
  MPI_Isend(sizes.data(), 2, MPI_INT64_T, target, tag_mesh_sizes, link_.inter(), &requests[0]);
  MPI_Isend(ids.data(), static_cast<int>(ids.size()), MPI_INT64_T, target, tag_mesh_ids, link_.inter(), &requests[1]);
  MPI_Isend(coordinates.data(), static_cast<int>(coordinates.size()), MPI_DOUBLE, target, tag_mesh_coordinates,
            link_.inter(), &requests[2]);
  MPI_Isend(flat_triangles.data(), static_cast<int>(flat_triangles.size()), MPI_INT64_T, target, tag_mesh_triangles,
            link_.inter(), &requests[3]);
  link_.wait(requests, "the fluid program to take the interface mesh");
  build_plan_structure();
}

void InterfaceExchange::build_plan_structure() {
  // Each fluid rank names, in its order, the vertices of this rank it exchanges.
  const int fluid_ranks = link_.partner_size();
  std::vector<std::int64_t> counts(static_cast<std::size_t>(fluid_ranks));
  std::vector<MPI_Request> requests(static_cast<std::size_t>(fluid_ranks));
  for (int f = 0; f < fluid_ranks; ++f)
    MPI_Irecv(&counts[static_cast<std::size_t>(f)], 1, MPI_INT64_T, f, tag_exchange_plan, link_.inter(),
              &requests[static_cast<std::size_t>(f)]);
  link_.wait(requests, "the exchange plan");
  std::vector<std::vector<std::int64_t>> lists(static_cast<std::size_t>(fluid_ranks));
  requests.assign(static_cast<std::size_t>(fluid_ranks), MPI_REQUEST_NULL);
  for (int f = 0; f < fluid_ranks; ++f) {
    auto& list = lists[static_cast<std::size_t>(f)];
    list.resize(static_cast<std::size_t>(counts[static_cast<std::size_t>(f)]));
    MPI_Irecv(list.data(), static_cast<int>(list.size()), MPI_INT64_T, f, tag_exchange_plan, link_.inter(),
              &requests[static_cast<std::size_t>(f)]);
  }
  link_.wait(requests, "the exchange plan");

  std::unordered_map<std::int64_t, int> index_of;
  for (std::size_t i = 0; i < mesh_.ids.size(); ++i) index_of[mesh_.ids[i]] = static_cast<int>(i);
  std::vector<int> times_listed(mesh_.ids.size(), 0);
  pair_vertices_.assign(static_cast<std::size_t>(fluid_ranks), {});
  for (int f = 0; f < fluid_ranks; ++f)
    for (const std::int64_t id : lists[static_cast<std::size_t>(f)]) {
      const auto it = index_of.find(id);
      if (it == index_of.end())
        throw CouplingError("exchange plan from fluid rank " + std::to_string(f) + " names vertex " +
                            std::to_string(id) + ", not declared on this structure rank");
      pair_vertices_[static_cast<std::size_t>(f)].push_back(it->second);
      ++times_listed[static_cast<std::size_t>(it->second)];
    }
  for (std::size_t i = 0; i < times_listed.size(); ++i)
    if (times_listed[i] != 1)
      throw CouplingError("exchange plan lists vertex " + std::to_string(mesh_.ids[i]) + " " +
                          std::to_string(times_listed[i]) + " times (once expected)");
  send_buffers_.resize(static_cast<std::size_t>(fluid_ranks));
}

// ---- fluid side ------------------------------------------------------------

InterfaceExchange::InterfaceExchange(PartnerLink& link) : link_(link) {
  // This rank receives the parts of structure ranks r with r mod size == rank.
  std::vector<std::int64_t> id_words, owner_words, triangle_ids;
  std::vector<double> coordinate_words;
  for (int s = link_.rank(); s < link_.partner_size(); s += link_.size()) {
    std::vector<std::int64_t> sizes(2);
    std::vector<MPI_Request> request(1);
    MPI_Irecv(sizes.data(), 2, MPI_INT64_T, s, tag_mesh_sizes, link_.inter(), &request[0]);
    link_.wait(request, "the interface mesh");
    if (sizes[0] < 0 || sizes[1] < 0) throw CouplingError("malformed interface mesh sizes from structure rank " + std::to_string(s));
    std::vector<std::int64_t> ids(static_cast<std::size_t>(sizes[0]));
    std::vector<double> coordinates(3 * ids.size());
    std::vector<std::int64_t> triangles(3 * static_cast<std::size_t>(sizes[1]));
    std::vector<MPI_Request> requests(3);
    MPI_Irecv(ids.data(), static_cast<int>(ids.size()), MPI_INT64_T, s, tag_mesh_ids, link_.inter(), &requests[0]);
    MPI_Irecv(coordinates.data(), static_cast<int>(coordinates.size()), MPI_DOUBLE, s, tag_mesh_coordinates,
              link_.inter(), &requests[1]);
    MPI_Irecv(triangles.data(), static_cast<int>(triangles.size()), MPI_INT64_T, s, tag_mesh_triangles, link_.inter(),
              &requests[2]);
    link_.wait(requests, "the interface mesh");
    id_words.insert(id_words.end(), ids.begin(), ids.end());
    owner_words.insert(owner_words.end(), ids.size(), s);
    coordinate_words.insert(coordinate_words.end(), coordinates.begin(), coordinates.end());
    triangle_ids.insert(triangle_ids.end(), triangles.begin(), triangles.end());
  }

  // Every fluid rank gets the whole mesh.
  const auto all_ids = all_gather(link_.local(), id_words);
  const auto all_owners = all_gather(link_.local(), owner_words);
  const auto all_coordinates = all_gather(link_.local(), coordinate_words);
  const auto all_triangles = all_gather(link_.local(), triangle_ids);

  std::vector<std::size_t> order(all_ids.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all_ids[a] < all_ids[b]; });
  std::vector<int> owner_of_sorted(order.size());
  mesh_.ids.resize(order.size());
  mesh_.coordinates.resize(3 * order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    if (k > 0 && all_ids[i] == mesh_.ids[k - 1])
      throw CouplingError("interface vertex id " + std::to_string(all_ids[i]) + " declared by structure ranks " +
                          std::to_string(owner_of_sorted[k - 1]) + " and " + std::to_string(all_owners[i]) +
                          " (each vertex must be declared by exactly one rank)");
    mesh_.ids[k] = all_ids[i];
    owner_of_sorted[k] = static_cast<int>(all_owners[i]);
    for (int c = 0; c < 3; ++c) mesh_.coordinates[3 * k + static_cast<std::size_t>(c)] = all_coordinates[3 * i + static_cast<std::size_t>(c)];
  }
  std::unordered_map<std::int64_t, int> index_of;
  for (std::size_t k = 0; k < mesh_.ids.size(); ++k) index_of[mesh_.ids[k]] = static_cast<int>(k);
  for (std::size_t t = 0; t + 2 < all_triangles.size(); t += 3) {
    std::array<int, 3> triangle{};
    for (int c = 0; c < 3; ++c) {
      const auto it = index_of.find(all_triangles[t + static_cast<std::size_t>(c)]);
      if (it == index_of.end())
        throw CouplingError("interface triangle " + std::to_string(t / 3) + " names vertex " +
                            std::to_string(all_triangles[t + static_cast<std::size_t>(c)]) + ", which no structure rank declared");
      triangle[static_cast<std::size_t>(c)] = it->second;
    }
    if (triangle[0] == triangle[1] || triangle[1] == triangle[2] || triangle[0] == triangle[2])
      throw CouplingError("interface triangle " + std::to_string(t / 3) + " repeats a vertex");
    mesh_.triangles.push_back(triangle);
  }
  global_vertices_ = mesh_.ids.size();
  build_plan_fluid(owner_of_sorted);
}

void InterfaceExchange::build_plan_fluid(const std::vector<int>& owner_of_sorted_vertex) {
  const auto ranks = static_cast<std::size_t>(link_.size());
  const std::size_t n = global_vertices_;
  slice_counts_.resize(ranks);
  slice_offsets_.resize(ranks);
  for (std::size_t f = 0; f < ranks; ++f) {
    const std::size_t begin = n * f / ranks;
    const std::size_t end = n * (f + 1) / ranks;
    slice_offsets_[f] = static_cast<int>(3 * begin);
    slice_counts_[f] = static_cast<int>(3 * (end - begin));
  }
  const auto me = static_cast<std::size_t>(link_.rank());
  const std::size_t first_vertex = static_cast<std::size_t>(slice_offsets_[me]) / 3;
  const std::size_t slice_vertices = static_cast<std::size_t>(slice_counts_[me]) / 3;
  slice_offset_ = 3 * first_vertex;
  part_size_ = 3 * slice_vertices;

  const int structure_ranks = link_.partner_size();
  pair_vertices_.assign(static_cast<std::size_t>(structure_ranks), {});
  std::vector<std::vector<std::int64_t>> lists(static_cast<std::size_t>(structure_ranks));
  for (std::size_t k = 0; k < slice_vertices; ++k) {
    const int owner = owner_of_sorted_vertex[first_vertex + k];
    pair_vertices_[static_cast<std::size_t>(owner)].push_back(static_cast<int>(k));
    lists[static_cast<std::size_t>(owner)].push_back(mesh_.ids[first_vertex + k]);
  }
  std::vector<std::int64_t> counts(static_cast<std::size_t>(structure_ranks));
  std::vector<MPI_Request> requests;
  for (int s = 0; s < structure_ranks; ++s) {
    counts[static_cast<std::size_t>(s)] = static_cast<std::int64_t>(lists[static_cast<std::size_t>(s)].size());
    requests.emplace_back();
    MPI_Isend(&counts[static_cast<std::size_t>(s)], 1, MPI_INT64_T, s, tag_exchange_plan, link_.inter(), &requests.back());
  }
  link_.wait(requests, "the structure program to take the exchange plan");
  for (int s = 0; s < structure_ranks; ++s) {
    const auto& list = lists[static_cast<std::size_t>(s)];
    requests.emplace_back();
    MPI_Isend(list.data(), static_cast<int>(list.size()), MPI_INT64_T, s, tag_exchange_plan, link_.inter(),
              &requests.back());
  }
  link_.wait(requests, "the structure program to take the exchange plan");
  send_buffers_.resize(static_cast<std::size_t>(structure_ranks));
}

// ---- every window ----------------------------------------------------------

std::vector<double> InterfaceExchange::reduce_to_slice(std::span<const double> partial_whole) const {
  if (partial_whole.size() != 3 * global_vertices_)
    throw CouplingError("fluid interface array of " + std::to_string(partial_whole.size()) + " values, expected " +
                        std::to_string(3 * global_vertices_));
  std::vector<double> slice(part_size_);
  MPI_Reduce_scatter(partial_whole.data(), slice.data(), slice_counts_.data(), MPI_DOUBLE, MPI_SUM, link_.local());
  return slice;
}

std::vector<double> InterfaceExchange::gather_slices(std::span<const double> slice) const {
  std::vector<double> whole(3 * global_vertices_);
  MPI_Allgatherv(slice.data(), static_cast<int>(slice.size()), MPI_DOUBLE, whole.data(), slice_counts_.data(),
                 slice_offsets_.data(), MPI_DOUBLE, link_.local());
  return whole;
}

void InterfaceExchange::post_sends(std::span<const double> part, int tag, std::size_t values_per_vertex) {
  const std::size_t width = values_per_vertex;
  if (part.size() != part_size_ / 3 * width)
    throw CouplingError("interface part of " + std::to_string(part.size()) + " values, expected " +
                        std::to_string(part_size_ / 3 * width));
  finish_sends("the partner to take earlier interface data");
  for (std::size_t p = 0; p < pair_vertices_.size(); ++p) {
    const auto& positions = pair_vertices_[p];
    if (positions.empty()) continue;
    auto& buffer = send_buffers_[p];
    buffer.resize(width * positions.size());
    for (std::size_t k = 0; k < positions.size(); ++k)
      for (std::size_t c = 0; c < width; ++c)
        buffer[width * k + c] = part[width * static_cast<std::size_t>(positions[k]) + c];
    send_requests_.emplace_back();
    MPI_Isend(buffer.data(), static_cast<int>(buffer.size()), MPI_DOUBLE, static_cast<int>(p), tag, link_.inter(),
              &send_requests_.back());
  }
}

std::vector<double> InterfaceExchange::receive_part(int tag, const std::string& what, std::size_t values_per_vertex) {
  const std::size_t width = values_per_vertex;
  std::vector<std::vector<double>> buffers(pair_vertices_.size());
  std::vector<MPI_Request> requests;
  for (std::size_t p = 0; p < pair_vertices_.size(); ++p) {
    if (pair_vertices_[p].empty()) continue;
    buffers[p].resize(width * pair_vertices_[p].size());
    requests.emplace_back();
    MPI_Irecv(buffers[p].data(), static_cast<int>(buffers[p].size()), MPI_DOUBLE, static_cast<int>(p), tag,
              link_.inter(), &requests.back());
  }
  link_.wait(requests, what);
  std::vector<double> part(part_size_ / 3 * width);
  for (std::size_t p = 0; p < pair_vertices_.size(); ++p)
    for (std::size_t k = 0; k < pair_vertices_[p].size(); ++k)
      for (std::size_t c = 0; c < width; ++c)
        part[width * static_cast<std::size_t>(pair_vertices_[p][k]) + c] = buffers[p][width * k + c];
  return part;
}

void InterfaceExchange::finish_sends(const std::string& what) { link_.wait(send_requests_, what); }

}  // namespace tankfsi::coupling
