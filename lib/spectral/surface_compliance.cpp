#include "lib/spectral/surface_compliance.hpp"

#include <stdexcept>

namespace wr {

void check_body(const ElasticBody& b) {
  if (!(b.young > 0)) throw std::invalid_argument("Young's modulus must be > 0");
  if (!(b.poisson > -1 && b.poisson < 0.5)) throw std::invalid_argument("Poisson's ratio must lie in (-1, 0.5)");
  if (!(b.thickness > 0)) throw std::invalid_argument("the layer thickness must be > 0 (inf: half-space)");
}

double normal_compliance(const ElasticBody& b, double q) {
  if (q <= 0) return b.half_space() ? std::numeric_limits<double>::infinity() : b.thickness / b.p_wave_modulus();
  const double half = 2 / (b.e_star() * q);
  if (b.half_space()) return half;
  const double x = q * b.thickness, nu = b.poisson, k = 3 - 4 * nu;
  // Beyond x = 20 the layer factor differs from 1 by less than e^-40 x^2.
  if (x > 20) return half;
  if (x < 1e-4) {
    // Series of the layer factor near 0: x (1 - 2 nu) / (2 (1 - nu)^2) + O(x^3).
    return half * x * (1 - 2 * nu) / (2 * (1 - nu) * (1 - nu));
  }
  const double num = k * std::sinh(2 * x) - 2 * x;
  const double den = k * std::cosh(2 * x) + 2 * x * x + 5 - 12 * nu + 8 * nu * nu;
  return half * num / den;
}

TangentialCompliance tangential_compliance(const ElasticBody& b, double qx, double qy) {
  TangentialCompliance c;
  const double q2 = qx * qx + qy * qy;
  if (q2 <= 0) return c;
  const double q = std::sqrt(q2), G = b.young / (2 * (1 + b.poisson)), nu = b.poisson;
  c.cxx = (1 - nu * qx * qx / q2) / (G * q);
  c.cyy = (1 - nu * qy * qy / q2) / (G * q);
  c.cxy = -nu * qx * qy / q2 / (G * q);
  c.cxz = (1 - 2 * nu) * qx / (2 * G * q2);
  c.cyz = (1 - 2 * nu) * qy / (2 * G * q2);
  return c;
}

double shear_compliance_mean(const ElasticBody& b) {
  if (b.half_space()) return std::numeric_limits<double>::infinity();
  return b.thickness * 2 * (1 + b.poisson) / b.young;
}

}  // namespace wr
