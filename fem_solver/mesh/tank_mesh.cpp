#include "fem_solver/mesh/tank_mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

namespace tankfsi::fem {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

/// Ring node counts from the centre outwards for a disc-like surface of
/// `rings` rings whose k-th ring has horizontal radius radius_of(k): the outer
/// ring has `outer` nodes; inwards the count halves (at most once per ring) when the spacing would
/// drop below 0.7 of the target size (so elements stay between ~0.7 and ~1.4
/// of it), never below 4.
std::vector<int> ring_counts(int rings, int outer, double size, const std::function<double(int)>& radius_of) {
  std::vector<int> counts(static_cast<std::size_t>(rings + 1), 1);
  counts[static_cast<std::size_t>(rings)] = outer;
  for (int k = rings - 1; k >= 1; --k) {
    int n = counts[static_cast<std::size_t>(k + 1)];
    if (n % 2 == 0 && n / 2 >= 4 && two_pi * radius_of(k) / n < 0.7 * size) n /= 2;  // one halving per ring: the zipper joins 2:1 rings
    counts[static_cast<std::size_t>(k)] = n;
  }
  return counts;
}

/// Adds a disc-like surface (roof or bottom) whose outer ring is `outer_ring`
/// (existing nodes at angles 2 pi j / n). point(k, phi) places ring k at angle
/// phi; ring 0 is the centre. Between rings of equal count: quads (or two
/// triangles each when `triangles_only`); where the count halves: a zipper of
/// triangles; at the centre: a fan. `outward` orients the elements.
void add_disc(ShellMesh& mesh, const std::vector<int>& outer_ring, int rings, double size, int region,
              bool triangles_only, const std::function<Eigen::Vector3d(int, double)>& point,
              const std::function<double(int)>& radius_of, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& outward) {
  const auto counts = ring_counts(rings, static_cast<int>(outer_ring.size()), size, radius_of);
  std::vector<std::vector<int>> ring_nodes(static_cast<std::size_t>(rings + 1));
  ring_nodes[static_cast<std::size_t>(rings)] = outer_ring;
  mesh.nodes.push_back(point(0, 0.0));
  ring_nodes[0] = {static_cast<int>(mesh.nodes.size()) - 1};
  for (int k = 1; k < rings; ++k) {
    const int n = counts[static_cast<std::size_t>(k)];
    for (int j = 0; j < n; ++j) {
      mesh.nodes.push_back(point(k, two_pi * j / n));
      ring_nodes[static_cast<std::size_t>(k)].push_back(static_cast<int>(mesh.nodes.size()) - 1);
    }
  }
  auto add = [&](std::array<int, 4> nodes) {
    const int count = nodes[3] < 0 ? 3 : 4;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < count; ++k) centre += mesh.nodes[static_cast<std::size_t>(nodes[static_cast<std::size_t>(k)])];
    centre /= count;
    const auto& a = mesh.nodes[static_cast<std::size_t>(nodes[0])];
    const auto& b = mesh.nodes[static_cast<std::size_t>(nodes[1])];
    const auto& c = mesh.nodes[static_cast<std::size_t>(nodes[2])];
    if ((b - a).cross(c - a).dot(outward(centre)) < 0.0) std::reverse(nodes.begin(), nodes.begin() + count);
    mesh.elements.push_back(MeshElement{nodes, region});
  };
  // Centre fan.
  const auto& first = ring_nodes[1];
  for (std::size_t j = 0; j < first.size(); ++j) add({ring_nodes[0][0], first[j], first[(j + 1) % first.size()], -1});
  for (int k = 1; k < rings; ++k) {
    const auto& inner = ring_nodes[static_cast<std::size_t>(k)];
    const auto& outer = ring_nodes[static_cast<std::size_t>(k + 1)];
    const std::size_t ni = inner.size();
    const std::size_t no = outer.size();
    if (ni == no) {
      for (std::size_t j = 0; j < ni; ++j) {
        const int a = inner[j], b = inner[(j + 1) % ni], c = outer[(j + 1) % no], d = outer[j];
        if (triangles_only) {
          add({a, b, c, -1});
          add({a, c, d, -1});
        } else {
          add({a, b, c, d});
        }
      }
      continue;
    }
    // Outer ring has twice the nodes: per inner segment, three triangles.
    for (std::size_t j = 0; j < ni; ++j) {
      const int a = inner[j], b = inner[(j + 1) % ni];
      const int o0 = outer[2 * j], o1 = outer[2 * j + 1], o2 = outer[(2 * j + 2) % no];
      add({a, o1, o0, -1});
      add({a, b, o1, -1});
      add({b, o2, o1, -1});
    }
  }
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

ShellMesh tank_mesh(const TankSpec& spec) {
  if (!(spec.radius > 0.0 && spec.wall_height > 0.0 && spec.element_size > 0.0))
    throw std::invalid_argument("a tank needs a positive radius, wall height and element size");
  const bool roofed = spec.dome_radius != 0.0;
  if (roofed && spec.dome_radius < spec.radius)
    throw std::invalid_argument("the dome radius must be at least the tank radius (or 0: an open top)");
  const double h = spec.element_size;
  // Around: a multiple of 8 so the rings can halve twice and keep the
  // tank's x and y symmetry planes on nodes.
  const int around = std::max(16, 8 * static_cast<int>(std::ceil(two_pi * spec.radius / h / 8.0)));
  const int layers = std::max(1, static_cast<int>(std::ceil(spec.wall_height / h)));
  ShellMesh mesh;
  const int wall = mesh.region_index("wall");
  const int roof = roofed ? mesh.region_index("roof") : -1;
  const int bottom = mesh.region_index("bottom");
  for (int j = 0; j <= layers; ++j)
    for (int i = 0; i < around; ++i) {
      const double phi = two_pi * i / around;
      mesh.nodes.emplace_back(spec.radius * std::cos(phi), spec.radius * std::sin(phi), spec.wall_height * j / layers);
    }
  const auto wall_node = [&](int i, int j) { return (i % around) + around * j; };
  for (int j = 0; j < layers; ++j)
    for (int i = 0; i < around; ++i)  // phi then z: normal away from the axis
      mesh.elements.push_back(MeshElement{{wall_node(i, j), wall_node(i + 1, j), wall_node(i + 1, j + 1), wall_node(i, j + 1)}, wall});
  std::vector<int> foot, top;
  for (int i = 0; i < around; ++i) {
    foot.push_back(wall_node(i, 0));
    top.push_back(wall_node(i, layers));
  }
  const std::size_t wall_elements = mesh.elements.size();

  // Roof: sphere cap through the wall's top ring, centre on the axis below it.
  const double half_angle = roofed ? std::asin(spec.radius / spec.dome_radius) : 0.0;
  const double centre_z = spec.wall_height - spec.dome_radius * std::cos(half_angle);
  const int roof_rings = std::max(2, static_cast<int>(std::ceil(spec.dome_radius * half_angle / h)));
  const Eigen::Vector3d sphere_centre(0.0, 0.0, centre_z);
  if (roofed) {
    add_disc(
        mesh, top, roof_rings, h, roof, false,
        [&](int k, double phi) {
          const double theta = half_angle * k / roof_rings;
          return Eigen::Vector3d(spec.dome_radius * std::sin(theta) * std::cos(phi),
                                 spec.dome_radius * std::sin(theta) * std::sin(phi),
                                 centre_z + spec.dome_radius * std::cos(theta));
        },
        [&](int k) { return spec.dome_radius * std::sin(half_angle * k / roof_rings); },
        [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(x - sphere_centre); });
  }
  const std::size_t roof_end = mesh.elements.size();

  // Bottom: flat disc of triangles at z = 0.
  const std::size_t bottom_first_node = mesh.nodes.size();
  const int bottom_rings = std::max(2, static_cast<int>(std::ceil(spec.radius / h)));
  add_disc(
      mesh, foot, bottom_rings, h, bottom, true,
      [&](int k, double phi) {
        const double r = spec.radius * k / bottom_rings;
        return Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), 0.0);
      },
      [&](int k) { return spec.radius * k / bottom_rings; }, [](const Eigen::Vector3d&) { return Eigen::Vector3d(0.0, 0.0, -1.0); });

  // Exact normals: radial on the wall (junction rings included: the roof and
  // bottom elements there are beyond the crease angle and average their own),
  // spherical on the roof, down on the bottom.
  mesh.node_normals.assign(mesh.nodes.size(), Eigen::Vector3d::Zero());
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Eigen::Vector3d& x = mesh.nodes[n];
    if (n < static_cast<std::size_t>(around * (layers + 1))) mesh.node_normals[n] = Eigen::Vector3d(x.x(), x.y(), 0.0);
    else if (n < bottom_first_node) mesh.node_normals[n] = x - sphere_centre;
    else mesh.node_normals[n] = Eigen::Vector3d(0.0, 0.0, -1.0);
  }
  std::vector<int> base = foot;
  for (std::size_t n = bottom_first_node; n < mesh.nodes.size(); ++n) base.push_back(static_cast<int>(n));
  mesh.node_sets["base"] = sorted(base);
  mesh.node_sets["wall_top"] = sorted(top);
  if (spec.liquid_level > 0.0) {
    std::vector<int> wetted;
    for (std::size_t e = 0; e < wall_elements; ++e) {
      double z = 0.0;
      for (const int n : mesh.elements[e].nodes) z += 0.25 * mesh.nodes[static_cast<std::size_t>(n)].z();
      if (z < spec.liquid_level) wetted.push_back(static_cast<int>(e));
    }
    for (std::size_t e = roof_end; e < mesh.elements.size(); ++e) wetted.push_back(static_cast<int>(e));
    mesh.element_sets["wetted"] = wetted;
  }
  return mesh;
}

}  // namespace tankfsi::fem
