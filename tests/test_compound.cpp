// The compound's viscoelastic master curve (lib/friction/compound.hpp): Prony series limits and
// the single Maxwell element's loss peak in closed form, the WLF shift, the file's errors.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "lib/core/errors.hpp"
#include "lib/friction/compound.hpp"
#include "lib/friction/modulus_table.hpp"

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

std::string compound_refusal(const nlohmann::json& j) {
  try {
    parse_compound_json(j.dump(), "c.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read without an error)";
}

// Issue 54, class 9 and bar 3: a compound whose cost has no bound is refused in one line before
// any work: the friction model's cost grows with the terms (20,000 took minutes), and a table's
// fit with its rows and the decades its frequencies span.
TEST(Compound, FilesWhoseCostHasNoBoundAreRefusedBeforeWork) {
  nlohmann::json j = compound_to_json(one_maxwell_element());
  nlohmann::json terms = nlohmann::json::array();
  for (std::size_t i = 0; i < kMaxPronyTerms; ++i) terms.push_back({{"tau_s", std::pow(10.0, -12 + 1e-3 * double(i))}, {"de_pa", 1e5}});
  j["prony"]["terms"] = terms;
  EXPECT_EQ(parse_compound_json(j.dump(), "c.json").terms.size(), kMaxPronyTerms);  // the limit itself is read
  terms.push_back({{"tau_s", 1.0}, {"de_pa", 1e5}});
  for (int k = 0; k < 20000; ++k) terms.push_back({{"tau_s", 1.0}, {"de_pa", 1e5}});
  j["prony"]["terms"] = terms;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = compound_refusal(j);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
  EXPECT_NE(e.find("c.json: prony.terms: 21001 terms; at most 1000"), std::string::npos) << e;

  // Tables: rows, decades, and frequencies whose relaxation times leave the doubles (1 / 5e-324
  // is inf: the fit's term count was then a cast of infinity).
  nlohmann::json t = compound_to_json(one_maxwell_element());
  t.erase("prony");
  auto table = [&](const std::vector<double>& omega) {
    std::vector<double> st(omega.size(), 1e7), lo(omega.size(), 1e6);
    t["table"] = {{"omega_rad_s", omega}, {"storage_pa", st}, {"loss_pa", lo}};
    return compound_refusal(t);
  };
  std::vector<double> many;
  for (std::size_t k = 0; k <= kMaxTableRows; ++k) many.push_back(1.0 + double(k));
  EXPECT_NE(table(many).find("table: 2001 frequencies; at most 2000"), std::string::npos);
  EXPECT_NE(table({1e-25, 1e-10, 1e5, 1e20}).find("span more than 40 decades"), std::string::npos);
  EXPECT_NE(table({5e-324, 1e-322, 1e-321, 1e-320}).find("table row 0: omega must lie in [1e-30, 1e30]"), std::string::npos);
  EXPECT_NE(table({1, 10, 100, 1e300}).find("table row 3: omega must lie in"), std::string::npos);
}

TEST(Compound, RelaxationTimesAreBoundedAndTheModulusStaysFinite) {
  nlohmann::json j = compound_to_json(one_maxwell_element());
  j["prony"]["terms"][0]["tau_s"] = 1e300;
  EXPECT_NE(compound_refusal(j).find("prony.terms[0].tau_s must be a time in [1e-40, 1e40] s"), std::string::npos);
  j["prony"]["terms"][0]["tau_s"] = 1e-4;
  j["prony"]["terms"][0]["de_pa"] = 1.7e308;
  j["prony"]["terms"].push_back({{"tau_s", 1e-3}, {"de_pa", 1.7e308}});
  EXPECT_NE(compound_refusal(j).find("glassy modulus"), std::string::npos);
  // The longest relaxation time at a high (shifted) frequency: (omega tau)^2 overflows; the term
  // is then fully glassy, E = E_r + dE, not inf / inf = NaN.
  Compound c = one_maxwell_element();
  c.terms[0].tau = kMaxTau;
  const std::complex<double> e = c.modulus_at_reference(1e130);
  EXPECT_EQ(e.real(), c.glassy_modulus());
  EXPECT_GE(e.imag(), 0.0);
  EXPECT_LT(e.imag(), 1e-60);
}

TEST(Compound, ByteOrderMarkIsSkippedAndTheShippedCompoundReads) {
  const std::string text = "\xEF\xBB\xBF" + compound_to_json(one_maxwell_element()).dump(1);
  EXPECT_EQ(parse_compound_json(text, "bom.json").terms.size(), 1u);
  const std::string e = [&] {
    try {
      parse_compound_json("{\"name\": \"Stra\xDF" "e\"}", "l1.json");
    } catch (const InputError& x) {
      return std::string(x.what());
    }
    return std::string();
  }();
  EXPECT_NE(e.find("l1.json: not valid JSON"), std::string::npos) << e;  // latin-1 is not JSON text
  EXPECT_NE(e.find("line 1, column"), std::string::npos) << e;
}

}  // namespace
}  // namespace wr
