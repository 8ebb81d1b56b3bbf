// Validation of the thin-film (Reynolds) flow on the map (lib/flow/thin_film_flow.hpp) against
// exact answers: parallel plates, 1-D corrugations (arithmetic / harmonic means, with the grid
// convergence of smooth and kinked profiles), rotation, contact lines, a dilute disc (Maxwell
// Garnett), the two solvers against each other, and bad input. Runs in a PETSc session (the amg
// solver).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "lib/core/errors.hpp"
#include "lib/flow/thin_film_flow.hpp"

namespace wr {
namespace {

constexpr double pi = std::numbers::pi;

HeightMap uniform_gap(std::size_t nx, std::size_t ny, double dx, double dy, double g) {
  HeightMap m(nx, ny, dx, dy);
  for (double& v : m.h) v = g;
  return m;
}

FlowOptions with(FlowSolver s) {
  FlowOptions o;
  o.solver = s;
  return o;
}

TEST(ThinFilmFlow, ParallelPlatesGiveCubeLaw) {
  const double g = 3e-6, c = g * g * g / 12;
  for (FlowSolver s : {FlowSolver::cholmod, FlowSolver::amg}) {
    const HeightMap m = uniform_gap(24, 17, 2e-5, 3e-5, g);  // unequal spacings and sizes
    FlowField f;
    const FlowConductance k = thin_film_conductance(m, with(s), &f);
    EXPECT_NEAR(k.kxx / c, 1.0, 1e-12);
    EXPECT_NEAR(k.kyy / c, 1.0, 1e-12);
    EXPECT_NEAR(k.kxy / c, 0.0, 1e-12);
    EXPECT_NEAR(k.kyx / c, 0.0, 1e-12);
    EXPECT_TRUE(k.percolates_x && k.percolates_y);
    EXPECT_EQ(k.free_fraction, 1.0);
    EXPECT_NEAR(k.mean_gap / g, 1.0, 1e-14);
    EXPECT_EQ(k.solver, flow_solver_name(s));
    ASSERT_EQ(f.flux_x.size(), m.size());
    EXPECT_NEAR(f.flux_x[5] / c, 1.0, 1e-12);  // the local flux of a unit gradient, eta = 1
    EXPECT_NEAR(f.pressure[3] - f.pressure[4], m.dx, 1e-12 * m.dx);  // p = -x + const
  }
}

// <(b + a cos t)^3> and <(b + a cos t)^-3> over a period (a < b): the continuum means of g^3.
double mean_cube(double b, double a) { return b * b * b + 1.5 * b * a * a; }
double mean_inverse_cube(double b, double a) { return (b * b + 0.5 * a * a) / std::pow(b * b - a * a, 2.5); }

// g(x) on n cells across x (x_i = i dx), repeated over `rows` rows: a corrugation with ridges along y.
template <class F>
HeightMap corrugation(std::size_t n, std::size_t rows, double period, F g) {
  HeightMap m(n, rows, period / double(n), 1e-5);
  for (std::size_t j = 0; j < rows; ++j)
    for (std::size_t i = 0; i < n; ++i) m(i, j) = g(double(i) * m.dx);
  return m;
}

// Along the ridges K_yy = <g^3>/12, across them K_xx = 1 / <12 / g^3>: the discrete means of the
// cells exactly, the continuum's by the rectangle rule, spectrally convergent for a smooth profile.
TEST(ThinFilmFlow, SmoothCorrugationConvergesSpectrally) {
  const double L = 1e-3, g0 = 2e-6, a = 1e-6;
  const double along = mean_cube(g0, a) / 12, across = 1 / (12 * mean_inverse_cube(g0, a));
  std::vector<double> err;
  for (std::size_t n : {8, 16, 32, 64}) {
    const HeightMap m = corrugation(n, 3, L, [&](double x) { return g0 + a * std::cos(2 * pi * x / L); });
    const FlowConductance k = thin_film_conductance(m, {});
    EXPECT_NEAR(k.kyy / along, 1.0, 1e-12) << n;  // g^3 is a trigonometric polynomial of degree 3: exact for n >= 4
    EXPECT_EQ(k.kxy, k.kxy);
    err.push_back(std::abs(k.kxx / across - 1));
  }
  // The integrand's poles at cos t = -g0/a = -2 lie acosh(2) = 1.317 off the real axis: the error
  // falls like exp(-1.317 n): measured 1.7e-3, 1.5e-7, 2e-14 (n = 8, 16, 32).
  EXPECT_GT(err[0] / err[1], 100.0);
  EXPECT_LT(err[1], 1e-6);
  EXPECT_LT(err[2], 1e-12);
  EXPECT_LT(err[3], 1e-12);
}

// A triangle wave between g0 - a and g0 + a: g is uniformly distributed over that range, so
// <g^3> = ((g0+a)^4 - (g0-a)^4) / (8a) and <g^-3> = ((g0-a)^-2 - (g0+a)^-2) / (4a). The kinks make the
// rectangle rule second order (measured across: 2.1e-2, 5.5e-3, 1.4e-3 at n = 20, 40, 80;
// 5.3e-7 at 4096).
TEST(ThinFilmFlow, TriangleCorrugationConvergesAtSecondOrder) {
  const double L = 1e-3, g0 = 2e-6, a = 1e-6;
  const double along = (std::pow(g0 + a, 4) - std::pow(g0 - a, 4)) / (8 * a) / 12;
  const double across = 1 / (12 * (std::pow(g0 - a, -2) - std::pow(g0 + a, -2)) / (4 * a));
  auto tri = [&](double x) {
    const double s = x / L - std::floor(x / L);  // 0 ... 1: from the crest down and back up
    return g0 + a * (4 * std::abs(s - 0.5) - 1);
  };
  std::vector<double> ex, ey;
  for (std::size_t n : {20, 40, 80, 4096}) {
    const FlowConductance k = thin_film_conductance(corrugation(n, 1, L, tri), {});
    ex.push_back(std::abs(k.kxx / across - 1));
    ey.push_back(std::abs(k.kyy / along - 1));
  }
  for (const auto* e : {&ex, &ey}) {
    const double order1 = std::log2((*e)[0] / (*e)[1]), order2 = std::log2((*e)[1] / (*e)[2]);
    EXPECT_NEAR(order1, 2.0, 0.05);
    EXPECT_NEAR(order2, 2.0, 0.05);
    EXPECT_LT((*e)[3], 1e-6);
  }
}

// For any positive profile the discrete answer is the cells' own means, to round-off.
TEST(ThinFilmFlow, RandomProfileGivesDiscreteMeansExactly) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.2e-6, 3e-6);
  std::vector<double> g(37);
  for (double& v : g) v = u(rng);
  double arith = 0, inv = 0;
  for (double v : g) {
    arith += v * v * v / 12 / double(g.size());
    inv += 12 / (v * v * v) / double(g.size());
  }
  HeightMap m(g.size(), 5, 1e-5, 2e-5);
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t i = 0; i < g.size(); ++i) m(i, j) = g[i];
  const FlowConductance k = thin_film_conductance(m, {});
  EXPECT_NEAR(k.kxx * inv, 1.0, 1e-12);
  EXPECT_NEAR(k.kyy / arith, 1.0, 1e-12);
  EXPECT_NEAR(k.kxy / arith, 0.0, 1e-12);
}

// A smooth random periodic gap with oblique waves (so K has off-diagonal terms), cut at a level:
// contact patches (gap 0) cover `contact` of it roughly.
HeightMap random_gap(std::size_t nx, std::size_t ny, unsigned seed, double level = 0.3) {
  HeightMap m(nx, ny, 1e-5, 1.3e-5);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> kx(-4, 4), ky(-3, 3);
  std::uniform_real_distribution<double> ph(0, 2 * pi), amp(0.5, 1.0);
  std::vector<double> h(m.size(), 0.0);
  for (int w = 0; w < 24; ++w) {
    const int a = kx(rng), b = ky(rng);
    const double phase = ph(rng), s = amp(rng) / std::sqrt(1.0 + a * a + b * b);
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        h[j * nx + i] += s * std::cos(2 * pi * (a * double(i) / double(nx) + b * double(j) / double(ny)) + phase);
  }
  // A tilt along (1, 1) in the wave content: stretch one oblique wave so the tensor is not diagonal.
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) h[j * nx + i] += 1.5 * std::cos(2 * pi * (double(i) / double(nx) + double(j) / double(ny)));
  for (std::size_t k = 0; k < m.size(); ++k) m.h[k] = std::max(0.0, level - h[k]) * 1e-6;
  return m;
}

// Rotated by 90 degrees, (x, y) -> (-y, x): K' = R K R^T, so K'_xx = K_yy, K'_yy = K_xx, K'_xy = -K_yx.
TEST(ThinFilmFlow, RotationTransposesTheSymmetricTensor) {
  const HeightMap m = random_gap(48, 36, 3);
  HeightMap r(m.ny, m.nx, m.dy, m.dx);
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) r(m.ny - 1 - j, i) = m(i, j);
  const FlowConductance k = thin_film_conductance(m, {}), kr = thin_film_conductance(r, {});
  const double scale = std::sqrt(k.kxx * k.kyy);
  ASSERT_GT(scale, 0);
  EXPECT_GT(std::abs(k.kxy) / scale, 0.01) << "the test map should have off-diagonal terms";
  EXPECT_LT(k.free_fraction, 0.95);
  EXPECT_NEAR(k.kxy / scale, k.kyx / scale, 1e-10);  // symmetric
  EXPECT_NEAR(kr.kxx / k.kyy, 1.0, 1e-10);
  EXPECT_NEAR(kr.kyy / k.kxx, 1.0, 1e-10);
  EXPECT_NEAR(kr.kxy / scale, -k.kyx / scale, 1e-10);
  EXPECT_GT(k.kxx * k.kyy - k.kxy * k.kyx, 0);  // positive definite
  EXPECT_EQ(k.percolates_x, kr.percolates_y);
  EXPECT_EQ(k.percolates_y, kr.percolates_x);
}

// A full row of contact shuts every face across it: no flow in y at all, exactly, while the
// other rows carry the plates' flux in x.
TEST(ThinFilmFlow, ContactLineBlocksFlowAcrossIt) {
  const double g = 2e-6, c = g * g * g / 12;
  HeightMap m = uniform_gap(32, 20, 1e-5, 1e-5, g);
  for (std::size_t i = 0; i < m.nx; ++i) m(i, 7) = 0;
  for (FlowSolver s : {FlowSolver::cholmod, FlowSolver::amg}) {
    const FlowConductance k = thin_film_conductance(m, with(s));
    EXPECT_TRUE(k.percolates_x);
    EXPECT_FALSE(k.percolates_y);
    EXPECT_EQ(k.kyy, 0.0);
    EXPECT_EQ(k.kxy, 0.0);
    EXPECT_EQ(k.kyx, 0.0);
    EXPECT_NEAR(k.kxx / (c * 19 / 20), 1.0, 1e-10);
    EXPECT_NEAR(k.free_fraction, 19.0 / 20, 1e-15);
  }
  const Percolation p = free_area_percolation(m);
  EXPECT_TRUE(p.x);
  EXPECT_FALSE(p.y);
  // A column too: nothing percolates, K = 0 exactly and no solve.
  for (std::size_t j = 0; j < m.ny; ++j) m(11, j) = 0;
  const FlowConductance k = thin_film_conductance(m, {});
  EXPECT_FALSE(k.percolates_x || k.percolates_y);
  EXPECT_EQ(k.kxx, 0.0);
  EXPECT_EQ(k.kyy, 0.0);
  EXPECT_EQ(k.solver, "none");
  EXPECT_EQ(k.unknowns, 0u);
}

// Free cells touching only at corners are not connected (4-connectivity): a diagonal line of
// free cells percolates nowhere; a staircase (each step shares a face) winds in x and in y, and
// its flux follows the diagonal, so K_xy > 0.
TEST(ThinFilmFlow, DiagonalChannelsAndConnectivity) {
  const std::size_t n = 16;
  HeightMap diag = uniform_gap(n, n, 1e-5, 1e-5, 0);
  for (std::size_t i = 0; i < n; ++i) diag(i, i) = 1e-6;
  const Percolation p = free_area_percolation(diag);
  EXPECT_FALSE(p.x || p.y);
  EXPECT_EQ(thin_film_conductance(diag, {}).kxx, 0.0);
  HeightMap stair = diag;
  for (std::size_t i = 0; i < n; ++i) stair((i + 1) % n, i) = 1e-6;
  const FlowConductance k = thin_film_conductance(stair, {});
  EXPECT_TRUE(k.percolates_x && k.percolates_y);
  EXPECT_GT(k.kxy, 0);
  EXPECT_NEAR(k.kxy / k.kyx, 1.0, 1e-10);
  // One channel: the tensor has rank one (flux only along the channel), det K = 0.
  EXPECT_NEAR((k.kxx * k.kyy - k.kxy * k.kyx) / (k.kxx * k.kyy), 0.0, 1e-9);
  // An isolated pocket of water: no through-flow.
  HeightMap pocket = uniform_gap(n, n, 1e-5, 1e-5, 0);
  for (std::size_t j = 4; j < 9; ++j)
    for (std::size_t i = 3; i < 10; ++i) pocket(i, j) = 1e-6;
  const FlowConductance kp = thin_film_conductance(pocket, {});
  EXPECT_FALSE(kp.percolates_x || kp.percolates_y);
  EXPECT_EQ(kp.kxx, 0.0);
  EXPECT_EQ(kp.kyy, 0.0);
  EXPECT_NEAR(kp.free_fraction, 35.0 / 256, 1e-15);
}

// A disc of contact (an insulating inclusion) in a uniform gap: for a square array of discs at
// area fraction phi, Rayleigh (Phil. Mag. 34, 481 (1892)) gives K/c = 1 - 2 phi / (1 + phi - 0.3058 phi^4 + ...),
// Maxwell Garnett's (1 - phi)/(1 + phi) to O(phi^4). The staircase disc of the grid differs from the
// circle by about a cell at its rim: at radius 45 cells this is measured at -0.23 % (phi = 0.099); 1 % allowed.
TEST(ThinFilmFlow, ContactDiscMatchesRayleigh) {
  const std::size_t n = 256;
  const double g = 1e-6, c = g * g * g / 12, r = 45.5;
  HeightMap m = uniform_gap(n, n, 1e-5, 1e-5, g);
  std::size_t closed = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i)
      if (std::hypot(double(i) - 127.5, double(j) - 127.5) < r) {
        m(i, j) = 0;
        ++closed;
      }
  const double phi = double(closed) / double(n * n);
  const double rayleigh = 1 - 2 * phi / (1 + phi - 0.3058 * std::pow(phi, 4));
  const FlowConductance k = thin_film_conductance(m, {});
  EXPECT_NEAR(k.kxx / k.kyy, 1.0, 1e-10);  // the square symmetry of the disc on the grid
  EXPECT_NEAR(k.kxy / k.kxx, 0.0, 1e-10);
  EXPECT_NEAR(k.kxx / (c * rayleigh), 1.0, 1e-2) << "phi " << phi;
}

TEST(ThinFilmFlow, CholmodAndAmgAgree) {
  const HeightMap m = random_gap(160, 128, 11, 0.5);
  const FlowConductance d = thin_film_conductance(m, with(FlowSolver::cholmod));
  FlowOptions o = with(FlowSolver::amg);
  o.tolerance = 1e-12;
  const FlowConductance a = thin_film_conductance(m, o);
  ASSERT_TRUE(d.percolates_x && d.percolates_y);
  const double scale = std::max(d.kxx, d.kyy);
  EXPECT_NEAR(a.kxx / scale, d.kxx / scale, 1e-8);
  EXPECT_NEAR(a.kyy / scale, d.kyy / scale, 1e-8);
  EXPECT_NEAR(a.kxy / scale, d.kxy / scale, 1e-8);
  EXPECT_EQ(d.iterations, 0);
  EXPECT_GT(a.iterations, 0);
  EXPECT_LT(d.residual, 1e-12);
  EXPECT_LT(a.residual, 1e-12);
  EXPECT_EQ(a.unknowns, d.unknowns);
  // The field's cell means are the tensor's column of the x solve.
  FlowField f;
  thin_film_conductance(m, {}, &f);
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < m.size(); ++k) {
    mx += f.flux_x[k] / double(m.size());
    my += f.flux_y[k] / double(m.size());
  }
  EXPECT_NEAR(mx / d.kxx, 1.0, 1e-12);
  EXPECT_NEAR(my / scale, d.kyx / scale, 1e-12);
}

TEST(ThinFilmFlow, BadInputIsRefused) {
  HeightMap m = uniform_gap(8, 8, 1e-5, 1e-5, 1e-6);
  HeightMap neg = m, nan = m, inf = m, open = m, empty;
  neg(3, 2) = -1e-9;
  nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  inf(1, 1) = std::numeric_limits<double>::infinity();
  open.periodic = false;
  for (const HeightMap* bad : {&neg, &nan, &inf, &open, &empty}) {
    EXPECT_THROW(thin_film_conductance(*bad, {}), InputError);
    EXPECT_THROW(free_area_percolation(*bad), InputError);
  }
  FlowOptions o;
  o.tolerance = 0;
  EXPECT_THROW(thin_film_conductance(m, o), InputError);
  EXPECT_THROW(parse_flow_solver("direct", "--solver"), InputError);
  EXPECT_EQ(parse_flow_solver("amg", "--solver"), FlowSolver::amg);
  EXPECT_EQ(parse_flow_solver("auto", "--solver"), FlowSolver::automatic);
  EXPECT_EQ(parse_flow_solver("cholmod", "--solver"), FlowSolver::cholmod);
}

}  // namespace
}  // namespace wr
