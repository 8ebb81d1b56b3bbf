// The compound's viscoelastic master curve (lib/friction/compound.hpp): Prony series limits and
// the single Maxwell element's loss peak in closed form, the WLF shift, the file's errors.
#include <gtest/gtest.h>

#include <cmath>

#include "lib/core/errors.hpp"
#include "lib/friction/compound.hpp"

namespace wr {
namespace {

Compound one_maxwell_element() {
  Compound c;
  c.name = "one Maxwell element";
  c.source = "test";
  c.synthetic = true;
  c.reference_temperature = 20;
  c.wlf_c1 = 8.86;
  c.wlf_c2 = 101.6;
  c.poisson = 0.5;
  c.e_relaxed = 2e6;
  c.terms = {{1e-4, 1e8}};
  return c;
}

TEST(Compound, SingleMaxwellElementMatchesItsClosedForm) {
  const Compound c = one_maxwell_element();
  const double tau = 1e-4, de = 1e8, er = 2e6;
  // Rubbery and glassy limits.
  EXPECT_NEAR(c.modulus_at_reference(0).real(), er, 1e-9 * er);
  EXPECT_EQ(c.modulus_at_reference(0).imag(), 0.0);
  EXPECT_NEAR(c.modulus_at_reference(1e12 / tau).real(), er + de, 1e-9 * (er + de));
  EXPECT_DOUBLE_EQ(c.glassy_modulus(), er + de);
  // E'' = dE x / (1 + x^2), largest (dE / 2) at x = omega tau = 1; E' = Er + dE x^2 / (1 + x^2).
  for (double x : {0.01, 0.3, 1.0, 3.0, 100.0}) {
    const std::complex<double> e = c.modulus_at_reference(x / tau);
    EXPECT_NEAR(e.imag(), de * x / (1 + x * x), 1e-12 * de) << x;
    EXPECT_NEAR(e.real(), er + de * x * x / (1 + x * x), 1e-12 * de) << x;
  }
  EXPECT_NEAR(c.modulus_at_reference(1 / tau).imag(), de / 2, 1e-9 * de);
  EXPECT_LT(c.modulus_at_reference(0.9 / tau).imag(), de / 2);
  EXPECT_LT(c.modulus_at_reference(1.1 / tau).imag(), de / 2);
}

TEST(Compound, WlfShiftMovesTheCurveAlongFrequency) {
  const Compound c = one_maxwell_element();
  EXPECT_EQ(c.log10_shift(20), 0.0);
  // 30 K above Tref: log aT = -8.86 * 30 / 131.6.
  EXPECT_NEAR(c.log10_shift(50), -8.86 * 30 / 131.6, 1e-14);
  const double a = std::pow(10.0, c.log10_shift(50));
  for (double w : {1.0, 1e3, 1e6}) {
    const auto shifted = c.modulus(w, 50), reference = c.modulus_at_reference(w * a);
    EXPECT_NEAR(shifted.real(), reference.real(), 1e-12 * std::abs(reference));
    EXPECT_NEAR(shifted.imag(), reference.imag(), 1e-12 * std::abs(reference));
  }
  // Warmer rubber is softer at a given frequency; the loss peak moves to higher frequency.
  EXPECT_LT(c.modulus(1e3, 50).real(), c.modulus(1e3, 20).real());
  EXPECT_THROW(c.log10_shift(20 - 101.6), InputError);  // the WLF pole
}

TEST(Compound, JsonRoundTripAndErrorsNameTheKey) {
  const Compound c = one_maxwell_element();
  const Compound back = compound_from_json(compound_to_json(c), "rt.json");
  EXPECT_EQ(back.name, c.name);
  EXPECT_TRUE(back.synthetic);
  ASSERT_EQ(back.terms.size(), 1u);
  EXPECT_EQ(back.terms[0].tau, c.terms[0].tau);
  EXPECT_EQ(back.modulus(123.0, 35.0), c.modulus(123.0, 35.0));
  const auto expect_error = [](nlohmann::json j, const std::string& needle) {
    try {
      compound_from_json(j, "bad.json");
      FAIL() << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  nlohmann::json j = compound_to_json(c);
  j.erase("prony");
  expect_error(j, "prony");
  j = compound_to_json(c);
  j["prony"]["e_relaxed_pa"] = -1e6;
  expect_error(j, "e_relaxed_pa");
  j = compound_to_json(c);
  j["prony"]["terms"][0]["de_pa"] = -5;
  expect_error(j, "prony.terms[0].de_pa");
  j = compound_to_json(c);
  j["prony"]["terms"][0]["tau_s"] = 0;
  expect_error(j, "tau_s");
  j = compound_to_json(c);
  j["poisson"] = 0.7;
  expect_error(j, "poisson");
  j = compound_to_json(c);
  j["wlf"].erase("c2_k");
  expect_error(j, "c2_k");
  expect_error(nlohmann::json::array(), "JSON object");
}

}  // namespace
}  // namespace wr
