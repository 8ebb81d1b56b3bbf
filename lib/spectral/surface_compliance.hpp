#pragma once
// Surface compliance of a periodic elastic body in Fourier space: the normal displacement of
// its surface under a normal pressure p(x) = p_q e^{i q.x} is u_z = C(q) p_q.
//
// - Half-space (thickness = inf): C(q) = 2 / (E* q), E* = E / (1 - nu^2) (Boussinesq; the
//   thesis's eq. 3.26 in Fourier form). The mean (q = 0) displacement is unbounded: only load
//   control makes sense, and C(0) is reported as +inf.
// - Layer of thickness t whose far face is held fixed (bonded to a rigid plate: the FEM block's
//   displaced top), frictionless load on the free face:
//     C(q) = 2 / (E* q) * [(3 - 4 nu) sinh 2x - 2x] / [(3 - 4 nu) cosh 2x + 2 x^2 + 5 - 12 nu + 8 nu^2],
//   x = q t. It tends to the half-space for x -> inf and to t / M (uniaxial strain, P-wave
//   modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu))) for x -> 0, which is also C(0).
// Units: q in rad/m, C in m/Pa. Requires E > 0, -1 < nu < 0.5, t > 0.
#include <cmath>
#include <limits>

namespace wr {

struct ElasticBody {
  double young = 1.0;                                       // E, Pa
  double poisson = 0.45;                                    // nu
  double thickness = std::numeric_limits<double>::infinity();  // m; inf: half-space

  bool half_space() const { return std::isinf(thickness); }
  double e_star() const { return young / (1 - poisson * poisson); }
  double p_wave_modulus() const { return young * (1 - poisson) / ((1 + poisson) * (1 - 2 * poisson)); }
};

// Throws std::invalid_argument for an unphysical body.
void check_body(const ElasticBody& body);

// m/Pa; q >= 0.
double normal_compliance(const ElasticBody& body, double q);

// The coupled surface Green tensor of the half-space in Fourier space (Boussinesq-Cerruti;
// Johnson, Contact Mechanics, eq. 2.18-2.19), for the body above its face: u_z positive into
// the body, p the compressive normal traction, tau the tangential traction on the face:
//   u_x = cxx tau_x + cxy tau_y + i cxz p,   u_y = cxy tau_x + cyy tau_y + i cyz p,
//   u_z = -i cxz tau_x - i cyz tau_y + C(q) p.
// The imaginary couplings carry the (1 - 2 nu) factor; they vanish for an incompressible body.
// For a layer of thickness t >= the period the half-space values are exact to ~(qt)^2 e^-2qt
// < 2e-4 at every non-zero lattice wave-vector; q = 0 is the layer's simple shear, u = t tau / G
// (shear_compliance_mean) with no coupling.
struct TangentialCompliance {
  double cxx = 0, cyy = 0, cxy = 0;  // m/Pa
  double cxz = 0, cyz = 0;           // m/Pa, imaginary parts
};
TangentialCompliance tangential_compliance(const ElasticBody& body, double qx, double qy);
// m/Pa: mean tangential face displacement per mean shear traction of a layer with its far
// face held (t / G); +inf for the half-space.
double shear_compliance_mean(const ElasticBody& body);

}  // namespace wr
