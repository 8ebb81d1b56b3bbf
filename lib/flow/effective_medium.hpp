#pragma once
// The mean-field rung of the thin-film flow: Bruggeman's effective-medium conductance of a
// rough interface from its contact fraction, mean separation and roughness, in microseconds.
// The exact rung solves Reynolds' equation on the map (lib/flow/thin_film_flow.hpp); the two
// are charted against each other in docs/validation.md ("Thin-film flow").
//
// Model (Persson's effective-medium picture of interfacial flow: Lorenz & Persson, Eur. Phys.
// J. E 31, 159 (2010); Dapp, Lücke, Persson & Müser, Phys. Rev. Lett. 108, 244301 (2012)):
//  - the interface is a 2-D random medium of local conductances sigma(u) = u^3 / 12 (parallel
//    plates at the local gap u; the tensor is isotropic);
//  - the gap distribution is P(u) = A delta(u) + (1 - A) f(u): the contact fraction A carries
//    no flow, the free gaps f follow the folded normal |N(m, h^2)| (Almqvist, Campañá, Prodanov &
//    Persson, J. Mech. Phys. Solids 59, 2355 (2011): the free gaps' distribution of an elastic
//    rough contact), h the roughness's rms height, m set so that the mean gap (1 - A) <u>_f is
//    the given mean separation (when even m = 0 gives too wide a spread, h shrinks instead);
//  - Bruggeman's self-consistency generalised to a percolation threshold A_c (a free fraction
//    1 - A_c), <(sigma - K) / (sigma + a K)> = 0 with a = A_c / (1 - A_c): a = 1 is the
//    symmetric 2-D medium (threshold at A = 1/2, a rigid flat cutting a Gaussian surface); the
//    elastic contact of self-affine surfaces stops percolating at A ~ 0.42 (Dapp et al.), the
//    default. K = 0 exactly for A >= A_c.
// Units: m, m^3 (K: the mean volume flux per unit width is -(K / eta) <grad p>).
namespace wr {

// The elastic contact's percolation threshold (Dapp et al. 2012) and the rigid flat's.
constexpr double kElasticPercolationContact = 0.42;
constexpr double kRigidPercolationContact = 0.5;

struct GapStatistics {
  double contact_fraction = 0;  // A in [0, 1]
  double mean_gap = 0;          // m, >= 0, over the whole nominal area (contact counted as 0)
  double rms_height = 0;        // m, >= 0: the spread of the free gaps
};

// K (m^3), >= 0. Throws std::invalid_argument for values outside the ranges above or A_c
// outside (0, 1). A zero rms gives parallel plates at gap mean_gap / (1 - A) in the medium.
double effective_medium_conductance(const GapStatistics& s, double critical_contact = kElasticPercolationContact);

}  // namespace wr
