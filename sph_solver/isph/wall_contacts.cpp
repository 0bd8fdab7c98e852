#include "sph_solver/isph/wall_contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "sph_solver/neighbours/neighbour_candidates.hpp"
#include "sph_solver/walls/closest_point.hpp"
#include "sph_solver/walls/mean_curvature.hpp"

namespace tankfsi::sph {
namespace {

/// Curvature the kernel resolves: |H| × support below this.
constexpr double resolvable_curvature = 0.5;

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// The tables for a wall of mean curvature H (see the header): Z_k - H C_k, never
/// past zero (a wall bulging so much that it leaves the support).
WallKernelValues curved(WallKernelValues v, double mean_curvature) {
  const auto bent = [mean_curvature](double z, double c) {
    const double value = z - mean_curvature * c;
    return value * z > 0.0 ? value : 0.0;
  };
  v.z0 = bent(v.z0, v.c0);
  v.z1 = bent(v.z1, v.c1);
  v.z2 = bent(v.z2, v.c2);
  v.z3 = bent(v.z3, v.c3);
  return v;
}

/// The order of a particle's wall hits: nearest first, ties by triangle index (a
/// strict total order: a particle meets each triangle once, so any sort gives the
/// same sequence).
bool nearer(const WallHit& a, const WallHit& b) {
  return a.closest.squared_distance < b.closest.squared_distance ||
         (a.closest.squared_distance == b.closest.squared_distance && a.triangle < b.triangle);
}

/// Sorts hits that are nearly in order already (a candidate list, sorted where it
/// was searched, whose points then moved by a fraction of the cutoff): an
/// insertion sort moves each hit only past those it overtook.
void sort_nearly_sorted(std::vector<WallHit>& hits) {
  for (std::size_t k = 1; k < hits.size(); ++k) {
    if (!nearer(hits[k], hits[k - 1])) continue;
    const WallHit hit = hits[k];
    std::size_t m = k;
    for (; m > 0 && nearer(hit, hits[m - 1]); --m) hits[m] = hits[m - 1];
    hits[m] = hit;
  }
}

/// The smooth wall's normal at barycentric w of triangle t; `plane` (the
/// triangle's own, as the contact uses it) where all three corners have it.
Eigen::Vector3d smooth_normal(const WallCornerValues& corners, int t, const Eigen::Vector3d& w,
                              const Eigen::Vector3d& plane, int dimension) {
  const auto& n = corners.normals(t);
  Eigen::Vector3d normal = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
  if (dimension == 2) normal.z() = 0.0;
  if (!(normal.norm() > 0.5)) return plane;  // corners on opposite walls: cannot happen on a manifold mesh
  normal.normalize();
  if (normal.dot(plane) < 0.0) normal = -normal;  // the back of a two-sided sheet
  return (normal - plane).squaredNorm() < 1e-24 ? plane : normal;
}

}  // namespace

WallModel::WallModel(TriangleMesh mesh, const FluidModel& model, const Kernel& kernel)
    : mesh_(std::make_unique<TriangleMesh>(std::move(mesh))),
      index_(*mesh_),
      table_(kernel, model.spacing),
      corner_table_(kernel, model.spacing),
      support_radius_(kernel.support_radius()),
      corner_values_(*mesh_),
      velocities_(mesh_->vertex_count(), Eigen::Vector3d::Zero()) {
  update_curvature();
}

void WallModel::replace_mesh(TriangleMesh mesh, std::vector<char> two_sided) {
  if (!two_sided.empty() && two_sided.size() != mesh.triangle_count())
    throw std::invalid_argument("WallModel::replace_mesh: one two-sided flag per triangle is needed");
  two_sided_ = std::move(two_sided);
  *mesh_ = std::move(mesh);  // the same object: the index keeps pointing to it
  index_.rebuild();
  velocities_.assign(mesh_->vertex_count(), Eigen::Vector3d::Zero());
  corner_values_ = WallCornerValues(*mesh_);
  update_curvature();
}

void WallModel::move(std::span<const Eigen::Vector3d> positions, std::span<const Eigen::Vector3d> velocities) {
  if (velocities.size() != mesh_->vertex_count())
    throw std::invalid_argument("WallModel::move: one velocity per vertex is needed");
  mesh_->move_vertices(positions);
  index_.refit();
  velocities_.assign(velocities.begin(), velocities.end());
  update_curvature();
}

void WallModel::update_curvature() {
  compute_vertex_mean_curvature(*mesh_, curvature_);
  for (double& h : curvature_)
    if (!(std::abs(h) * support_radius_ <= resolvable_curvature)) h = std::numeric_limits<double>::quiet_NaN();
  corner_values_.update(*mesh_, curvature_);
}

WallCandidates find_wall_candidates(const WallModel& walls, std::span<const Eigen::Vector3d> positions,
                                    double skin) {
  if (!(std::isfinite(skin) && skin >= 0.0))
    throw std::invalid_argument("find_wall_candidates: the skin must be finite and at least 0");
  WallCandidates result;
  result.searched.assign(positions.begin(), positions.end());
  result.skin = skin;
  result.wall_version = walls.mesh().geometry_version();
  result.offsets.reserve(positions.size() + 1);
  const TriangleMesh& mesh = walls.mesh();
  const TriangleIndex& index = walls.index();
  const double radius = walls.table().cutoff() + skin;
  const double radius_squared = radius * radius;
  // Runs of consecutive points (the particles are in cell order: neighbours in
  // space) within a box as wide as the radius share one descent of the index;
  // each point then tests the run's triangles, their boxes first. (Measured on
  // cases/sloshing_cylinder_3d, 0.2 s: 17.18e9 instructions in all against
  // 17.39e9 with runs a third as wide, which there hold about one particle each.)
  const double run_extent = radius;
  std::vector<int> near_run;
  for (std::size_t first = 0; first < positions.size();) {
    Eigen::AlignedBox3d run(positions[first]);
    std::size_t end = first + 1;
    for (; end < positions.size(); ++end) {
      Eigen::AlignedBox3d grown = run;
      grown.extend(positions[end]);
      if (grown.sizes().maxCoeff() > run_extent) break;
      run = grown;
    }
    near_run.clear();
    index.near_box(run, radius, near_run);
    for (std::size_t i = first; i < end; ++i) {
      const Eigen::Vector3d& x = positions[i];
      for (const int t : near_run) {
        if (index.box(t).squaredExteriorDistance(x) >= radius_squared) continue;
        if (const auto closest = closest_point_within(x, mesh, t, radius_squared))
          result.hits.push_back(WallHit{t, *closest});
      }
      // In find_wall_contacts' order: at the point searched its hits within the
      // cutoff are then in order as they are, and near it nearly.
      std::sort(result.hits.begin() + result.offsets.back(), result.hits.end(), nearer);
      result.offsets.push_back(static_cast<int>(result.hits.size()));
    }
    first = end;
  }
  return result;
}

namespace {

/// Throws unless `candidates` may stand for a search at `positions`.
void require_usable(const WallCandidates& candidates, const WallModel& walls,
                    std::span<const Eigen::Vector3d> positions) {
  if (candidates.wall_version != walls.mesh().geometry_version())
    throw std::invalid_argument("find_wall_contacts: the wall moved since its candidates were found");
  require_moved_within(candidates.searched, positions, candidates.skin, "find_wall_contacts");
}

/// A wall met by a particle: its hits (indices into the sorted hits, nearest
/// first; one more than a contact keeps, for the smooth cut), the nearest one's
/// height over its plane and smooth normal (which decides what is the same wall).
struct WallSeen {
  std::array<std::size_t, max_wall_feet + 1> hits{};
  int hit_count = 1;
  double height = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// 1 at s = 0 falling to 0 at s = 1 with zero slope at both ends; 0 beyond.
double taper(double s) { return s >= 1.0 ? 0.0 : (1.0 - s) * (1.0 - s) * (1.0 + 2.0 * s); }

/// The contact of one wall from its hits, blended as find_wall_contacts describes.
WallContact blended_contact(const WallModel& walls, std::span<const WallHit> hits,
                            const std::vector<std::pair<Eigen::Vector3d, double>>& planes,
                            const std::vector<char>& from_behind, const WallSeen& wall, int dimension, double band) {
  const auto distance = [&hits, &wall](int f) {
    return std::sqrt(hits[wall.hits[static_cast<std::size_t>(f)]].closest.squared_distance);
  };
  const double nearest = distance(0);
  const int kept = std::min(wall.hit_count, max_wall_feet);
  const double floor = wall.hit_count > max_wall_feet ? taper((distance(max_wall_feet) - nearest) / band) : 0.0;
  WallContact contact;
  contact.foot_count = 0;
  double total = 0.0;
  for (int f = 0; f < kept; ++f) {
    const double weight = taper((distance(f) - nearest) / band) - floor;
    if (f > 0 && !(weight > 0.0)) break;  // sorted by distance: the rest weigh nothing either
    const WallHit& hit = hits[wall.hits[at(f)]];
    contact.feet[at(contact.foot_count++)] = WallFoot{hit.triangle, hit.closest.barycentric, weight};
    total += weight;
  }
  // All kept hits as far as the first left out (ties at the cut): the nearest alone.
  if (!(total > 0.0)) {
    contact.foot_count = 1;
    contact.feet[0].weight = total = 1.0;
  }
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double curvature = 0.0;
  Eigen::Matrix3d shape_deviator = Eigen::Matrix3d::Zero();
  double depth = 0.0;  // of the smooth wall behind the facets' planes
  for (int f = 0; f < contact.foot_count; ++f) {
    WallFoot& foot = contact.feet[at(f)];
    foot.weight /= total;
    const Eigen::Vector3d& plane = planes[wall.hits[at(f)]].first;
    normal += foot.weight * smooth_normal(walls.corner_values(), foot.triangle, foot.barycentric, plane, dimension);
    // Seen from behind, a wall that bulges towards the front is hollow.
    const double sign = from_behind[wall.hits[at(f)]] ? -1.0 : 1.0;
    curvature += sign * foot.weight * walls.corner_values().curvature_at(foot.triangle, foot.barycentric);
    shape_deviator += sign * foot.weight * walls.corner_values().shape_deviator(foot.triangle);
    depth += sign * foot.weight * walls.corner_values().smooth_depth(walls.mesh(), foot.triangle, foot.barycentric);
  }
  contact.normal = contact.foot_count == 1 ? wall.normal : normal.normalized();
  contact.distance = wall.height <= 0.0 ? 0.0 : std::max(0.0, nearest + depth);
  contact.values = curved(walls.table().at(contact.distance), curvature);
  contact.tangential_moment = tangential_moment(contact.values, contact.normal, shape_deviator, dimension);
  contact.velocity = at_contact(walls.mesh(), walls.vertex_velocities(), contact);
  return contact;
}

}  // namespace

Eigen::Matrix3d tangential_moment(const WallKernelValues& values, const Eigen::Vector3d& normal,
                                  const Eigen::Matrix3d& shape_deviator, int dimension) {
  const Eigen::Matrix3d along = Eigen::Matrix3d::Identity() - normal * normal.transpose();
  Eigen::Matrix3d moment = values.z3 * along;
  if (dimension == 3 && values.z3 > 0.0) {
    // The deviator in the plane normal to n (the feet's planes differ from it
    // slightly), traceless there again.
    const Eigen::Matrix3d in_plane = along * shape_deviator * along;
    moment -= 0.5 * values.c3 * (in_plane - 0.5 * in_plane.trace() * along);
  }
  return moment;
}

WallContacts find_wall_contacts(const WallModel& walls, std::span<const Eigen::Vector3d> positions, int dimension,
                                const WallCandidates* candidates) {
  if (candidates != nullptr) require_usable(*candidates, walls, positions);
  const TriangleMesh& mesh = walls.mesh();
  const double cutoff = walls.table().cutoff();
  const double cutoff_squared = cutoff * cutoff;
  const double crossing_tolerance = touching_depth * walls.table().spacing();
  const double beside_tolerance = 1e-9 * walls.table().spacing();  // round-off of a foot point
  WallContacts result;
  result.offsets.reserve(positions.size() + 1);
  result.overlap_offsets.reserve(positions.size() + 1);
  result.octant_offsets.reserve(positions.size() + 1);
  const double blend_band = wall_foot_blend_band * walls.table().spacing();
  std::vector<WallHit> found;  // where the hits are not the candidates' as they are
  std::vector<std::pair<Eigen::Vector3d, double>> planes;
  std::vector<char> from_behind;
  std::vector<WallSeen> walls_seen;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Eigen::Vector3d& x = positions[i];
    std::span<const WallHit> hits;  // nearest first
    found.clear();
    if (candidates == nullptr) {
      walls.index().within(x, cutoff, [&found](const WallHit& hit) { found.push_back(hit); });
      std::sort(found.begin(), found.end(), nearer);
      hits = found;
    } else if (x == candidates->searched[i]) {
      // The point searched: its candidates within the cutoff, the first of its
      // sorted list, with the closest points found then.
      const auto first = candidates->hits.begin() + candidates->offsets[i];
      const auto end = candidates->hits.begin() + candidates->offsets[i + 1];
      hits = std::span<const WallHit>(
          first, std::find_if(first, end, [cutoff_squared](const WallHit& h) {
            return !(h.closest.squared_distance < cutoff_squared);
          }));
    } else {
      // The index's own test (TriangleIndex::visit_within), on the candidates only.
      for (int k = candidates->offsets[i]; k < candidates->offsets[i + 1]; ++k) {
        const int t = candidates->hits[static_cast<std::size_t>(k)].triangle;
        if (const auto closest = closest_point_within(x, mesh, t, cutoff_squared)) found.push_back(WallHit{t, *closest});
      }
      sort_nearly_sorted(found);  // the candidates' order, mended where the point's move changed it
      hits = found;
    }
    // Each hit's plane normal (zero: not a wall of the plane) and the particle's height over it.
    // A two-sided triangle seen from behind, the particle right behind it (not
    // beside it: its sheet's free edge, or the rest of the sheet), turns round.
    planes.clear();
    from_behind.clear();
    for (const WallHit& hit : hits) {
      Eigen::Vector3d normal = wall_plane_normal(mesh, hit.triangle, dimension);
      double height = (x - hit.closest.point).dot(normal);
      const bool behind = height < 0.0 && walls.two_sided(hit.triangle) &&
                          (x - hit.closest.point - height * normal).norm() <= beside_tolerance;
      if (behind) normal = -normal, height = -height;
      planes.push_back({normal, height});
      from_behind.push_back(behind ? 1 : 0);
    }
    const auto first_contact = result.contacts.size();
    walls_seen.clear();
    for (std::size_t k = 0; k < hits.size(); ++k) {
      const WallHit& hit = hits[k];
      const Eigen::Vector3d normal = planes[k].first;
      const double height = planes[k].second;
      if (normal.squaredNorm() == 0.0) continue;  // not a wall of the plane, or degenerate
      if (height < 0.0) {
        // Behind the plane: touching if it crossed the triangle itself by a little.
        // Beside the triangle and in front of another wall it is round a convex edge
        // of the solid (flowing over a plate's top, below the top face's plane).
        // Beside a two-sided sheet (its free edge or the rest of it) it is round
        // the sheet's edge: a sheet has no inside to have crossed into.
        const double beside = (x - hit.closest.point - height * normal).norm();
        const bool round_convex_edge =
            beside > beside_tolerance &&
            (walls.two_sided(hit.triangle) || std::any_of(planes.begin(), planes.end(), [&normal](const auto& other) {
               return other.second > 0.0 && other.first.dot(normal) <= same_wall_cosine;
             }));
        if (height < -crossing_tolerance || round_convex_edge) continue;
      }
      const auto same_wall = std::find_if(walls_seen.begin(), walls_seen.end(), [&normal](const WallSeen& w) {
        return w.normal.dot(normal) > same_wall_cosine;
      });
      if (same_wall != walls_seen.end()) {
        // A further hit of a wall already met: a candidate foot of its contact.
        if (same_wall->hit_count <= max_wall_feet) same_wall->hits[at(same_wall->hit_count++)] = k;
        continue;
      }
      WallSeen wall;
      wall.hits[0] = k;
      wall.height = height;
      wall.normal = smooth_normal(walls.corner_values(), hit.triangle, hit.closest.barycentric, normal, dimension);
      walls_seen.push_back(wall);
    }
    for (const WallSeen& wall : walls_seen)
      result.contacts.push_back(blended_contact(walls, hits, planes, from_behind, wall, dimension, blend_band));
    result.offsets.push_back(static_cast<int>(result.contacts.size()));
    // Corners: orthogonal pairs of the particle's walls overlap behind both.
    const auto contacts = std::span<const WallContact>(result.contacts).subspan(first_contact);
    const auto orthogonal = [&contacts](std::size_t k, std::size_t l) {
      return std::abs(contacts[k].normal.dot(contacts[l].normal)) < BoundaryOverlap::orthogonal_cosine;
    };
    for (std::size_t k = 0; k < contacts.size(); ++k)
      for (std::size_t l = k + 1; l < contacts.size(); ++l) {
        if (!orthogonal(k, l)) continue;
        BoundaryOverlap overlap;
        overlap.first = static_cast<int>(k);
        overlap.second = static_cast<int>(l);
        overlap.normal_a = contacts[k].normal;
        overlap.normal_b = contacts[l].normal;
        overlap.values = walls.corner_table().at(contacts[k].distance, contacts[l].distance);
        if (overlap.values.q0 > 0.0 || overlap.values.q2 < 0.0) result.overlaps.push_back(overlap);
      }
    result.overlap_offsets.push_back(static_cast<int>(result.overlaps.size()));
    // Corners of three walls: the octant behind all three, once back in.
    if (dimension == 3)
      for (std::size_t k = 0; k < contacts.size(); ++k)
        for (std::size_t l = k + 1; l < contacts.size(); ++l)
          for (std::size_t m = l + 1; m < contacts.size(); ++m) {
            if (!(orthogonal(k, l) && orthogonal(k, m) && orthogonal(l, m))) continue;
            CornerOctant octant;
            octant.contacts = {static_cast<int>(k), static_cast<int>(l), static_cast<int>(m)};
            octant.normals = {contacts[k].normal, contacts[l].normal, contacts[m].normal};
            octant.values = walls.corner_table().octant(contacts[k].distance, contacts[l].distance, contacts[m].distance);
            if (octant.values.q0 > 0.0 || octant.values.q2 < 0.0) result.octants.push_back(octant);
          }
    result.octant_offsets.push_back(static_cast<int>(result.octants.size()));
  }
  return result;
}

Eigen::Vector3d wall_plane_normal(const TriangleMesh& mesh, int triangle, int dimension) {
  Eigen::Vector3d normal = mesh.face_normals()[at(triangle)];
  if (dimension == 2) {
    // The front and back of a 2D section's thin walls are not walls of the plane.
    if (std::abs(normal.z()) > 0.5) normal.setZero();
    normal.z() = 0.0;
    if (normal.squaredNorm() > 0.0) normal.normalize();
  }
  return normal;
}

Eigen::Vector3d at_contact(const TriangleMesh& mesh, std::span<const Eigen::Vector3d> vertex_values,
                           const WallContact& contact) {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  for_each_vertex_share(mesh, contact, [&](int v, double share) { value += share * vertex_values[at(v)]; });
  return value;
}

void add_wall_force(const TriangleMesh& mesh, const WallContact& contact, const Eigen::Vector3d& force,
                    std::vector<Eigen::Vector3d>& vertex_forces) {
  for_each_vertex_share(mesh, contact, [&](int v, double share) { vertex_forces[at(v)] += share * force; });
}

}  // namespace tankfsi::sph
