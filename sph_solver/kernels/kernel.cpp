#include "sph_solver/kernels/kernel.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>

namespace tankfsi::sph {

namespace {

constexpr double pi = std::numbers::pi;

// The two B-spline kernels are sums of truncated powers,
//   w(q) = sum_k c_k (a_k - q)_+^n,
// so one evaluator serves both (Schoenberg 1946; Monaghan 2005, Rep. Prog. Phys. 68:1703).
struct TruncatedPowerSum {
  int power;
  std::array<double, 3> coefficients;
  std::array<double, 3> knots;  ///< a_k, largest first; a_0 is the support in units of h
};

constexpr TruncatedPowerSum quintic_shape{5, {1.0, -6.0, 15.0}, {3.0, 2.0, 1.0}};
constexpr TruncatedPowerSum quartic_shape{4, {1.0, -5.0, 10.0}, {2.5, 1.5, 0.5}};
constexpr double wendland_support = 2.0;

double integer_power(double base, int exponent) {
  double result = 1.0;
  for (int k = 0; k < exponent; ++k) result *= base;
  return result;
}

double spline_shape(const TruncatedPowerSum& shape, double q) {
  double w = 0.0;
  for (std::size_t k = 0; k < shape.knots.size(); ++k) {
    if (q < shape.knots[k]) w += shape.coefficients[k] * integer_power(shape.knots[k] - q, shape.power);
  }
  return w;
}

// dw/dq = -n sum_k c_k (a_k - q)_+^(n-1). At q = 0 the sum cancels exactly in binary
// floating point (all a_k are dyadic), so dW/dr(0) = 0 without a special case.
double spline_shape_slope(const TruncatedPowerSum& shape, double q) {
  double slope = 0.0;
  for (std::size_t k = 0; k < shape.knots.size(); ++k) {
    if (q < shape.knots[k]) {
      slope -= shape.power * shape.coefficients[k] * integer_power(shape.knots[k] - q, shape.power - 1);
    }
  }
  return slope;
}

// w and dw/dq together: each term's (a_k - q)^(n-1) serves both (w takes one
// more factor, in the order integer_power multiplies, so the bits are the same).
void spline_shape_and_slope(const TruncatedPowerSum& shape, double q, double& w, double& slope) {
  w = 0.0;
  slope = 0.0;
  for (std::size_t k = 0; k < shape.knots.size(); ++k) {
    if (q < shape.knots[k]) {
      const double base = shape.knots[k] - q;
      const double lower = integer_power(base, shape.power - 1);
      w += shape.coefficients[k] * (lower * base);
      slope -= shape.power * shape.coefficients[k] * lower;
    }
  }
}

// Wendland C2 in q = r/h with support 2h (Dehnen & Aly 2012, rescaled from support 1):
// w = (1 - q/2)^4 (2q + 1);  dw/dq = (1 - q/2)^3 [-2(2q + 1) + 2(1 - q/2)] = -5 q (1 - q/2)^3.
double wendland_shape(double q) {
  if (q >= wendland_support) return 0.0;
  const double s = 1.0 - 0.5 * q;
  return s * s * s * s * (2.0 * q + 1.0);
}

double wendland_shape_slope(double q) {
  if (q >= wendland_support) return 0.0;
  const double s = 1.0 - 0.5 * q;
  return -5.0 * q * s * s * s;
}

double support_in_h(KernelType type) {
  switch (type) {
    case KernelType::quintic_spline: return quintic_shape.knots[0];
    case KernelType::quartic_spline: return quartic_shape.knots[0];
    case KernelType::wendland_c2: return wendland_support;
  }
  throw std::invalid_argument("kernel: unknown kernel type");
}

// alpha_D = 1 / (S_D * integral_0^support w(q) q^(D-1) dq), S_2 = 2 pi, S_3 = 4 pi.
// For a truncated power the integral is a Beta function:
//   integral_0^a (a - q)^n q^(D-1) dq = a^(n+D) n! (D-1)! / (n+D)!.
// Quintic, 2D: (3^7 - 6*2^7 + 15) / 42 = 239/7      -> alpha = 7/(478 pi)
//          3D: (3^8 - 6*2^8 + 15) / 168 = 30        -> alpha = 1/(120 pi)
// Quartic, 2D: (2.5^6 - 5*1.5^6 + 10*0.5^6) / 30 = 1199/192 -> alpha = 96/(1199 pi)
//          3D: (2.5^7 - 5*1.5^7 + 10*0.5^7) / 105 = 5       -> alpha = 1/(20 pi)
// Wendland C2 (polynomial on [0, 2], integrated term by term):
//          2D: integral = 2/7 -> alpha = 7/(4 pi);  3D: integral = 4/21 -> alpha = 21/(16 pi).
// The unit tests check every value by Gauss-Legendre quadrature and by lattice sums.
double normalisation(KernelType type, int dimension) {
  const bool planar = dimension == 2;
  switch (type) {
    case KernelType::quintic_spline: return planar ? 7.0 / (478.0 * pi) : 1.0 / (120.0 * pi);
    case KernelType::quartic_spline: return planar ? 96.0 / (1199.0 * pi) : 1.0 / (20.0 * pi);
    case KernelType::wendland_c2: return planar ? 7.0 / (4.0 * pi) : 21.0 / (16.0 * pi);
  }
  throw std::invalid_argument("kernel: unknown kernel type");
}

void require_dimension(int dimension) {
  if (dimension != 2 && dimension != 3) {
    throw std::invalid_argument("kernel: dimension must be 2 or 3, got " + std::to_string(dimension));
  }
}

}  // namespace

KernelType default_kernel(int dimension) {
  require_dimension(dimension);
  return dimension == 2 ? KernelType::quintic_spline : KernelType::quartic_spline;
}

double default_smoothing_length_ratio(KernelType type) {
  switch (type) {
    case KernelType::quintic_spline: return 1.2;
    case KernelType::quartic_spline: return 1.1;
    case KernelType::wendland_c2: return 1.5;
  }
  throw std::invalid_argument("default_smoothing_length_ratio: unknown kernel type");
}

KernelType parse_kernel_type(std::string_view word, int dimension) {
  require_dimension(dimension);
  if (word == "auto") return default_kernel(dimension);
  for (KernelType type : {KernelType::quintic_spline, KernelType::quartic_spline, KernelType::wendland_c2}) {
    if (word == kernel_name(type)) return type;
  }
  throw std::invalid_argument("kernel: unknown kernel '" + std::string(word) +
                              "' (expected auto, quintic_spline, quartic_spline or wendland_c2)");
}

std::string_view kernel_name(KernelType type) {
  switch (type) {
    case KernelType::quintic_spline: return "quintic_spline";
    case KernelType::quartic_spline: return "quartic_spline";
    case KernelType::wendland_c2: return "wendland_c2";
  }
  throw std::invalid_argument("kernel: unknown kernel type");
}

Kernel::Kernel(KernelType type, int dimension, double smoothing_length)
    : type_(type), dimension_(dimension), smoothing_length_(smoothing_length) {
  require_dimension(dimension);
  if (!std::isfinite(smoothing_length) || smoothing_length <= 0.0) {
    throw std::invalid_argument("kernel: smoothing length must be positive and finite");
  }
  inverse_smoothing_length_ = 1.0 / smoothing_length;
  support_radius_ = support_in_h(type) * smoothing_length;
  value_factor_ = normalisation(type, dimension) * integer_power(inverse_smoothing_length_, dimension);
  derivative_factor_ = value_factor_ * inverse_smoothing_length_;
}

double Kernel::value(double r) const {
  // Compare r itself with the support: q = r/h rounds, and could fall a hair inside it.
  if (r >= support_radius_) return 0.0;
  const double q = r * inverse_smoothing_length_;
  switch (type_) {
    case KernelType::quintic_spline: return value_factor_ * spline_shape(quintic_shape, q);
    case KernelType::quartic_spline: return value_factor_ * spline_shape(quartic_shape, q);
    case KernelType::wendland_c2: return value_factor_ * wendland_shape(q);
  }
  return 0.0;
}

double Kernel::derivative(double r) const {
  // Compare r itself with the support: q = r/h rounds, and could fall a hair inside it.
  if (r >= support_radius_) return 0.0;
  const double q = r * inverse_smoothing_length_;
  switch (type_) {
    case KernelType::quintic_spline: return derivative_factor_ * spline_shape_slope(quintic_shape, q);
    case KernelType::quartic_spline: return derivative_factor_ * spline_shape_slope(quartic_shape, q);
    case KernelType::wendland_c2: return derivative_factor_ * wendland_shape_slope(q);
  }
  return 0.0;
}

namespace {

// W and dW/dr of each radius, for one shape: the type is chosen once for a whole
// neighbour list rather than once per pair, and the loop body inlines.
template <class ShapeAndSlope>
void kernel_values(std::span<const double> radii, std::span<double> values, std::span<double> slopes,
                   double support_radius, double inverse_smoothing_length, double value_factor,
                   double derivative_factor, ShapeAndSlope shape_and_slope) {
  for (std::size_t k = 0; k < radii.size(); ++k) {
    double w = 0.0;
    double slope = 0.0;
    // Compare r itself with the support: q = r/h rounds, and could fall a hair inside it.
    if (radii[k] < support_radius) shape_and_slope(radii[k] * inverse_smoothing_length, w, slope);
    values[k] = w * value_factor;
    slopes[k] = slope * derivative_factor;
  }
}

}  // namespace

void Kernel::value_and_derivative(double r, double& value, double& slope) const {
  values_and_slopes(std::span<const double>(&r, 1), std::span<double>(&value, 1), std::span<double>(&slope, 1));
}

void Kernel::values_and_slopes(std::span<const double> radii, std::span<double> values,
                               std::span<double> slopes) const {
  if (values.size() != radii.size() || slopes.size() != radii.size())
    throw std::invalid_argument("kernel: values_and_slopes needs one value and one slope per radius");
  const auto run = [&](auto shape_and_slope) {
    kernel_values(radii, values, slopes, support_radius_, inverse_smoothing_length_, value_factor_,
                  derivative_factor_, shape_and_slope);
  };
  switch (type_) {
    case KernelType::quintic_spline:
      run([](double q, double& w, double& slope) { spline_shape_and_slope(quintic_shape, q, w, slope); });
      break;
    case KernelType::quartic_spline:
      run([](double q, double& w, double& slope) { spline_shape_and_slope(quartic_shape, q, w, slope); });
      break;
    case KernelType::wendland_c2:
      run([](double q, double& w, double& slope) {
        w = wendland_shape(q);
        slope = wendland_shape_slope(q);
      });
      break;
  }
}

Eigen::Vector3d Kernel::gradient(const Eigen::Vector3d& x_ij) const { return gradient(x_ij, x_ij.norm()); }

Eigen::Vector3d Kernel::gradient(const Eigen::Vector3d& x_ij, double r) const {
  // The direction x_ij/r is undefined at r = 0, where dW/dr = 0 anyway: the gradient is zero.
  if (r <= 0.0) return Eigen::Vector3d::Zero();
  return x_ij * (derivative(r) / r);
}

}  // namespace tankfsi::sph
