#include "lib/spectral/spectral_contact_test.hpp"

#include <chrono>
#include <cmath>

#include "lib/core/errors.hpp"

namespace wr {

void check_spectral_test_options(const SpectralTestOptions& opt) {
  const bool by_load = opt.pressure > 0;
  if (by_load == (opt.uz > 0)) throw InputError("--uz/--pressure", "give exactly one of --uz (m) and --pressure (Pa), > 0");
  if (!by_load && opt.body.half_space())
    throw InputError("--uz", "a half-space (--thickness inf) cannot be displacement-controlled; give --pressure");
  if (opt.steps < 1) throw InputError("--steps", "must be >= 1");
  if (!(opt.rms_slope > 0)) throw InputError("--surface", "the obstacle has no slope (flat surface)");
  try {
    check_body(opt.body);
  } catch (const std::invalid_argument& e) {
    throw InputError("--E/--nu/--thickness", e.what());
  }
}

SpectralTestResult run_spectral_normal_test(const HeightMap& obstacle, const SpectralTestOptions& opt,
                                            const std::function<void(const ContactStep&)>& on_step) {
  if (!obstacle.periodic) throw InputError("--surface", "the spectral model needs a periodic surface");
  check_spectral_test_options(opt);
  const bool by_load = opt.pressure > 0;
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  SpectralTestResult res;
  res.nx = obstacle.nx;
  res.ny = obstacle.ny;
  res.spacing = obstacle.dx;
  SpectralNormalContact solver(obstacle, opt.body, opt.solver.threads);
  res.wall_setup = std::chrono::duration<double>(clock::now() - t0).count();
  const double a0 = obstacle.lx() * obstacle.ly();
  for (int k = 1; k <= opt.steps; ++k) {
    const double frac = double(k) / opt.steps;
    const SpectralNormalResult r =
        by_load ? solver.solve_load(frac * opt.pressure, opt.solver) : solver.solve_approach(frac * opt.uz, opt.solver);
    ContactStep st;
    st.uz = r.approach;
    st.fz = r.mean_pressure * a0;
    st.area_fraction = r.area_fraction;
    st.contact_area = r.area_fraction * a0;
    st.sigma_star = r.mean_pressure / (opt.body.e_star() * opt.rms_slope);
    st.separation = r.mean_gap;
    st.max_penetration = r.max_penetration;
    st.signorini_iterations = 1;
    st.linear_iterations = r.iterations;
    st.wall_s = r.wall_s;
    st.wall_solve = r.wall_s;
    st.converged = r.converged;
    st.message = r.message;
    st.history = r.history;
    if (opt.face_maps) {
      st.face_pressure = solver.pressure();
      st.face_gap = solver.gap();
      st.face_status.resize(st.face_pressure.size());
      for (std::size_t i = 0; i < st.face_pressure.size(); ++i) st.face_status[i] = st.face_pressure[i] > 0 ? 1.0 : 0.0;
    }
    res.steps.push_back(std::move(st));
    if (on_step) on_step(res.steps.back());
    if (!r.converged) {
      res.failed = true;
      break;
    }
  }
  res.wall_s = std::chrono::duration<double>(clock::now() - t0).count();
  return res;
}

}  // namespace wr
