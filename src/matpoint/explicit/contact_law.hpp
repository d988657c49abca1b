// Lumped contact laws at one node (Nairn 2026 §3.2 eq. (18); Bardenhagen et al. 2001).
// Input: the momentum change dp0 that would move field a to the common (centre-of-mass) velocity,
// dp0 = m_red (v_b - v_a) (applied +dp to a, -dp to b), and the unit normal n from a to b.
//   approaching (in contact):  dp0 . n < 0
//   stick:         dp = dp0                                   (every shared node: single-field MPM)
//   frictionless:  dp = (dp0 . n) n
//   Coulomb:       dp = (dp0 . n) n + min(|dp0_t|, mu (-dp0 . n)) t,   t = dp0_t / |dp0_t|
// A_c and dt cancel from these laws (extraction §2.5 item 6), so none is needed.
#pragma once

#include "matpoint/core/types.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

/// The momentum change the law applies to field a (field b gets the opposite); zero when the
/// fields separate (dp0 . n >= 0) or, with `check_approach` false, never tested (stick).
template <int D>
Vec<D> contact_momentum_change(const ContactLawSpec& law, const Vec<D>& dp0, const Vec<D>& n) {
  if (law.law == ContactLaw::Stick) return dp0;
  const double dn = dp0.dot(n);
  if (!(dn < 0.0)) return Vec<D>::Zero();  // separating: no contact
  const Vec<D> normal = dn * n;
  if (law.law == ContactLaw::Frictionless) return normal;
  const Vec<D> tangential = dp0 - normal;
  const double dt = tangential.norm();
  const double limit = law.friction * (-dn);
  if (dt <= limit) return dp0;                // Coulomb stick
  return normal + (limit / dt) * tangential;  // slide: S_slide A_c dt = mu N_c A_c dt
}

}  // namespace matpoint
