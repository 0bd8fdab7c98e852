// The interface mesh and its values between any fluid:structure split: the
// fluid ranks hold the whole mesh in id order, partial forces arrive summed
// over the fluid's ranks at the owning structure rank, displacements reach
// every fluid rank, and broken meshes and mismatched partners are refused.
#include <catch2/catch.hpp>

#include <algorithm>

#include "coupling/interface/interface_exchange.hpp"
#include "coupling/participant.hpp"
#include "partner_split.hpp"

using namespace tankfsi::coupling;
using namespace tankfsi::coupling::testing;

namespace {

constexpr int vertex_total = 17;
std::int64_t id_of(int k) { return 7 * k + 3; }

struct Declared {
  std::vector<std::int64_t> ids;
  std::vector<double> coordinates;
  std::vector<std::array<std::int64_t, 3>> triangles;
};

// Structure rank r of B declares vertices k = r, r + B, ... (ids in no order
// the fluid could guess) and the triangles (k, k+1, k+2) of its k.
Declared declared_by(int rank, int ranks) {
  Declared d;
  for (int k = vertex_total - 1 - rank; k >= 0; k -= ranks) {
    d.ids.push_back(id_of(k));
    d.coordinates.insert(d.coordinates.end(), {double(k), 2.0 * k, 3.0 * k});
    if (k + 2 < vertex_total) d.triangles.push_back({id_of(k), id_of(k + 1), id_of(k + 2)});
  }
  return d;
}

}  // namespace

TEST_CASE("interface mesh and values on every split", "[coupling][interface]") {
  for (const int fluid_ranks : fluid_rank_choices()) {
    PartnerSplit split(fluid_ranks);
    CAPTURE(fluid_ranks);
    int rank = 0, size = 1;
    MPI_Comm_rank(split.local, &rank);
    MPI_Comm_size(split.local, &size);
    PartnerLink link(split.local, split.partner, split.side, 30.0);
    if (split.side == Side::structure) {
      const Declared d = declared_by(rank, size);
      InterfaceExchange exchange(link, d.ids, d.coordinates, d.triangles);
      // Forces: the sum over fluid ranks f of (f + 1)(id + c).
      const auto forces = exchange.receive_part(tag_force, "forces");
      const double rank_weights = 0.5 * fluid_ranks * (fluid_ranks + 1);
      for (std::size_t i = 0; i < d.ids.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
          CHECK(forces[3 * i + c] == Approx(rank_weights * double(d.ids[i] + static_cast<std::int64_t>(c))));
      // Displacements: 10 id + c from the owner.
      std::vector<double> displacement;
      for (const auto id : d.ids)
        for (int c = 0; c < 3; ++c) displacement.push_back(10.0 * double(id) + c);
      exchange.post_sends(displacement, tag_displacement);
      exchange.finish_sends("displacements taken");
    } else {
      InterfaceExchange exchange(link);
      const InterfaceMesh& mesh = exchange.mesh();
      REQUIRE(mesh.vertex_count() == static_cast<std::size_t>(vertex_total));
      CHECK(std::is_sorted(mesh.ids.begin(), mesh.ids.end()));
      for (int k = 0; k < vertex_total; ++k) {
        CHECK(mesh.ids[static_cast<std::size_t>(k)] == id_of(k));
        CHECK(mesh.coordinates[3 * static_cast<std::size_t>(k) + 2] == 3.0 * k);
      }
      REQUIRE(mesh.triangles.size() == static_cast<std::size_t>(vertex_total - 2));
      for (const auto& t : mesh.triangles) CHECK((t[1] == t[0] + 1 && t[2] == t[0] + 2));
      std::vector<double> partial(3 * mesh.vertex_count());
      for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
        for (std::size_t c = 0; c < 3; ++c) partial[3 * i + c] = (rank + 1.0) * double(mesh.ids[i] + static_cast<std::int64_t>(c));
      exchange.post_sends(exchange.reduce_to_slice(partial), tag_force);
      const auto whole = exchange.gather_slices(exchange.receive_part(tag_displacement, "displacements"));
      for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
        for (std::size_t c = 0; c < 3; ++c) CHECK(whole[3 * i + c] == 10.0 * double(mesh.ids[i]) + double(c));
      exchange.finish_sends("forces taken");
    }
  }
}

TEST_CASE("broken interface meshes are refused", "[coupling][interface]") {
  for (const int fluid_ranks : fluid_rank_choices()) {
    PartnerSplit split(fluid_ranks);
    int rank = 0, size = 1;
    MPI_Comm_rank(split.local, &rank);
    MPI_Comm_size(split.local, &size);
    // The structure waits for an exchange plan that never comes: short time-out.
    PartnerLink link(split.local, split.partner, split.side, 2.0);
    Declared d = declared_by(rank, size);
    d.triangles.push_back({id_of(0), id_of(1), 999});  // a vertex nobody declared
    if (split.side == Side::structure) {
      CHECK_THROWS_WITH(InterfaceExchange(link, d.ids, d.coordinates, d.triangles),
                        Catch::Contains("timed out") && Catch::Contains("exchange plan"));
    } else {
      CHECK_THROWS_WITH(InterfaceExchange(link), Catch::Contains("names vertex 999, which no structure rank declared"));
    }
  }
}

TEST_CASE("partners with other coupling settings refuse each other, naming the key", "[coupling][handshake]") {
  for (const int fluid_ranks : fluid_rank_choices()) {
    PartnerSplit split(fluid_ranks);
    CouplingSettings settings;
    settings.scheme = Scheme::sequential_staggered;
    settings.time_window = split.side == Side::fluid ? 0.01 : 0.02;
    Participant p(split.side, settings, split.local, split.partner, {{"fluid", "abc"}, {"structure", "def"}});
    if (split.side == Side::structure) p.set_interface({1}, {0, 0, 0}, {});
    CHECK_THROWS_WITH(p.exchange_interface(),
                      Catch::Contains(split.side == Side::fluid ? "coupling.time_window: fluid 0.01, structure 0.02"
                                                                : "coupling.time_window: structure 0.02, fluid 0.01"));
  }
}
