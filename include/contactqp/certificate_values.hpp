// The numbers of the optimality certificate (certificate.hpp says how each is computed): a
// header of its own so that SolveResult (qp.hpp) can carry them without the functions.
#pragma once

namespace contactqp {

struct Certificate {
  double stationarity = 0;        // relative (certificate.hpp)
  double primal_feasibility = 0;  // relative
  double dual_feasibility = 0;    // relative
  double complementarity = 0;     // relative
  double tangential = 0;          // relative natural-map residual of the friction law; 0 without friction
  double objective = 0;           // J(u), in the QP's energy units (with friction, Σ r_i‖slip_i‖ included)
  double dual_objective = 0;      // θ(λ); −inf is reported as not finite (K singular and f − Bᵀλ ∉ range K)
  double duality_gap = 0;         // J(u) − θ(λ), energy units; ≥ 0 up to round-off when u is feasible
  double relative_gap = 0;        // duality_gap / energy scale
  bool dual_available = true;     // false when K could not be factorised; θ and the gaps are then 0

  double kkt_max() const;  // the largest of the relative KKT residuals (tangential included)
};

}  // namespace contactqp
