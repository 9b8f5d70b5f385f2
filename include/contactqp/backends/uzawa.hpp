// The options of the uzawa and uzawa_accel backends (solvers/uzawa.cpp, uzawa_accel.cpp):
// how the step ρ is chosen. Set with SolveOptions::set(UzawaOptions{...}), or as text with
// --rho / a scene's solver.rho / Python's rho= (docs/rho.md).
#pragma once

namespace contactqp {

struct UzawaOptions {
  // How the step ρ is chosen. Auto estimates the spectrum of S = B K⁻¹ Bᵀ by Lanczos (one
  // solve per step) on the rows the unconstrained solution violates, and takes
  // ρ_opt = 2/(λ_min + λ_max) (uzawa) or 1/λ_max (uzawa_accel); Absolute takes `rho` in the
  // QP's own units (force per length); FractionOfMax takes `rho` as a fraction of
  // ρ_max = 2/λ_max(S) on those rows.
  enum class RhoRule { Auto, Absolute, FractionOfMax };
  RhoRule rho_rule = RhoRule::Auto;
  double rho = 0.0;
  // Set by solve() on its internally scaled copy: the caller's ρ per backend ρ, so that
  // messages quote ρ in the caller's units. Leave at 1.
  double rho_unit = 1.0;
};

}  // namespace contactqp
