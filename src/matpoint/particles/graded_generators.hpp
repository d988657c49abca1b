// Graded particle generators of Aulisa & Capodaglio, "Monolithic coupling of implicit material point
// method with finite element method" (Appendix A; §6.2, §6.3): a disk and a cantilever beam, each a
// uniform core wrapped in boundary layers whose spacing shrinks geometrically towards the surface.
//
// Both follow the authors' released code (the extraction's "[CODE]" variant, its §10), not the
// printed Appendix-A pseudocode: the pseudocode does not reproduce the particle counts of the paper
// (disk 46 982 instead of 48 739; the beam pseudocode places every layer on the core's top and bottom
// rows and gives about 5 364 particles with twice the mass). The code variant gives 48 738, 57 083
// and 23 040, one less than each of the paper's counts (extraction §10, item A11).
#pragma once

#include <cstddef>
#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint {

/// Particles of one graded body, 2-D. volume = mass / rho for every particle.
struct GradedParticles {
  std::vector<Vec<2>> position;
  std::vector<double> mass;
  std::vector<double> volume;
  std::size_t core_count = 0;  ///< particles of the uniform core (the first core_count entries)
  int layers = 0;              ///< boundary layers generated
};

/// Smallest n with sum_{k=1..n} f^-k >= target (the authors' getNumberOfLayers). Needs f > 1 and
/// target < 1/(f-1), the limit of the sum; throws std::invalid_argument otherwise.
int graded_layer_count(double target, double f);

/// Disk of radius R about centre: a centre particle and rings of equal-mass particles up to R0, then
/// boundary layers of ratio f out to about R (extraction §10.1 [CODE]). Particle 0 is the centre
/// particle, the point the paper tracks. Needs R >= R0 > 0, N_theta0 >= 7 (one core ring at least),
/// f > 1 and rho > 0; throws std::invalid_argument otherwise.
GradedParticles graded_disk(const Vec<2>& centre, double R, double R0, int N_theta0, double f, double rho);

/// Beam [x0, x0+L] x [y0-H/2, y0+H/2], (x0, y0) the centre of its left end: a core of N_H rows over
/// height H0, then boundary layers of ratio f on its top, right end and bottom (extraction §10.2
/// [CODE]). Needs 0 < H0 <= H, L > (H-H0)/2, N_H >= 2, f > 1 and rho > 0; throws std::invalid_argument
/// otherwise.
GradedParticles graded_beam(double x0, double y0, double H, double L, double H0, int N_H, double f,
                            double rho);

}  // namespace matpoint
