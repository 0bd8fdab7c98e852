// Nearest-projection mapping for partners with non-matching surface meshes:
// consistent mapping reproduces linear fields exactly, conservative mapping
// keeps the total force and its moment; and through the participant, a fluid
// with its own wall vertices reads the structure's displacements and gives it
// its forces, on every split.
#include <catch2/catch.hpp>

#include <cmath>

#include "coupling/mapping/nearest_projection.hpp"
#include "coupling/participant.hpp"
#include "partner_split.hpp"

using namespace tankfsi::coupling;
using namespace tankfsi::coupling::testing;

namespace {

// A 4 x 3 m plate in z = 0 meshed with n x m cells, two triangles each.
InterfaceMesh plate(int n, int m) {
  InterfaceMesh mesh;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) {
      mesh.ids.push_back(j * (n + 1) + i);
      mesh.coordinates.insert(mesh.coordinates.end(), {4.0 * i / n, 3.0 * j / m, 0.0});
    }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  return mesh;
}

// Own vertices: a finer, shifted grid slightly off the plate.
std::vector<double> own_points(double offset) {
  std::vector<double> p;
  for (int j = 0; j < 7; ++j)
    for (int i = 0; i < 11; ++i) p.insert(p.end(), {0.05 + 0.39 * i, 0.1 + 0.47 * j, offset});
  return p;
}

double linear_field(const double* x, int c) { return 0.001 * (c + 1) * (1.0 + 2.0 * x[0] - 0.5 * x[1]); }

}  // namespace

TEST_CASE("nearest projection: linear fields exactly, total force and moment kept", "[coupling][mapping]") {
  const InterfaceMesh mesh = plate(4, 3);
  const std::vector<double> points = own_points(0.002);
  const NearestProjection mapping(mesh, points);
  CHECK(mapping.max_distance() == Approx(0.002));
  std::vector<double> mesh_values(3 * mesh.vertex_count()), own(points.size());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int c = 0; c < 3; ++c) mesh_values[3 * v + static_cast<std::size_t>(c)] = linear_field(&mesh.coordinates[3 * v], c);
  mapping.consistent(mesh_values, own);
  for (std::size_t i = 0; i < points.size() / 3; ++i)
    for (int c = 0; c < 3; ++c) CHECK(own[3 * i + static_cast<std::size_t>(c)] == Approx(linear_field(&points[3 * i], c)));

  std::vector<double> forces(points.size());
  for (std::size_t i = 0; i < forces.size(); ++i) forces[i] = std::sin(1.0 + static_cast<double>(i));
  mapping.conservative(forces, mesh_values);
  for (int c = 0; c < 3; ++c) {
    double own_total = 0, mesh_total = 0, own_moment = 0, mesh_moment = 0;
    for (std::size_t i = 0; i < points.size() / 3; ++i) {
      own_total += forces[3 * i + static_cast<std::size_t>(c)];
      own_moment += points[3 * i] * forces[3 * i + static_cast<std::size_t>(c)];  // about the y axis (x lever)
    }
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      mesh_total += mesh_values[3 * v + static_cast<std::size_t>(c)];
      mesh_moment += mesh.coordinates[3 * v] * mesh_values[3 * v + static_cast<std::size_t>(c)];
    }
    CHECK(mesh_total == Approx(own_total).epsilon(1e-12));
    CHECK(mesh_moment == Approx(own_moment).epsilon(1e-12));
  }
  CHECK_THROWS(NearestProjection(InterfaceMesh{}, points));
}

TEST_CASE("a fluid with its own wall vertices couples through the mapping", "[coupling][mapping]") {
  for (const int fluid_ranks : fluid_rank_choices()) {
    PartnerSplit split(fluid_ranks);
    CAPTURE(fluid_ranks);
    CouplingSettings settings;
    settings.scheme = Scheme::parallel_staggered;
    settings.time_window = 0.1;
    settings.end_time = 0.3;
    settings.timeout = 30;
    Participant p(split.side, settings, split.local, split.partner);
    int rank = 0, size = 1;
    MPI_Comm_rank(split.local, &rank);
    MPI_Comm_size(split.local, &size);
    const InterfaceMesh mesh = plate(4, 3);
    const std::vector<double> points = own_points(0.0);
    std::vector<double> values;
    if (split.side == Side::structure) {
      // Each structure rank declares every size-th vertex and every size-th triangle.
      std::vector<std::int64_t> ids;
      std::vector<double> xyz;
      std::vector<std::array<std::int64_t, 3>> triangles;
      for (std::size_t v = static_cast<std::size_t>(rank); v < mesh.vertex_count(); v += static_cast<std::size_t>(size)) {
        ids.push_back(mesh.ids[v]);
        xyz.insert(xyz.end(), &mesh.coordinates[3 * v], &mesh.coordinates[3 * v] + 3);
        for (int c = 0; c < 3; ++c) values.push_back(linear_field(&mesh.coordinates[3 * v], c));
      }
      for (std::size_t t = static_cast<std::size_t>(rank); t < mesh.triangles.size(); t += static_cast<std::size_t>(size))
        triangles.push_back({mesh.triangles[t][0], mesh.triangles[t][1], mesh.triangles[t][2]});
      p.set_interface(ids, xyz, triangles);
      p.exchange_interface();
      p.write(Field::displacement, values);  // the field from the start
    } else {
      p.set_own_vertices(points);
      p.exchange_interface();
      values.assign(points.size(), 0.0);
      // Rank 0 writes a uniform 2 N along z at every own vertex, the others nothing.
      for (std::size_t i = 0; rank == 0 && i < points.size() / 3; ++i) values[3 * i + 2] = 2.0;
      p.write(Field::force, values);
    }
    p.initialize();
    std::vector<double> read(p.value_count());
    while (p.is_ongoing()) {
      const double dt = p.max_time_step();
      if (split.side == Side::fluid) {
        p.read(Field::displacement, dt, read);
        for (std::size_t i = 0; i < points.size() / 3; ++i)
          for (int c = 0; c < 3; ++c) CHECK(read[3 * i + static_cast<std::size_t>(c)] == Approx(linear_field(&points[3 * i], c)));
        p.write(Field::force, values);
      } else {
        p.read(Field::force, dt, read);
        double local = 0.0, total = 0.0;
        for (std::size_t v = 0; v < read.size() / 3; ++v) local += read[3 * v + 2];
        MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, split.local);
        CHECK(total == Approx(2.0 * static_cast<double>(points.size() / 3)));
        p.write(Field::displacement, values);
      }
      p.advance(dt);
    }
    p.finalize();
  }
}
