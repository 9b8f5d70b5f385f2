// The options of the nlopt backend (solvers/nlopt.cpp). Set with SolveOptions::set(NloptOptions{...}),
// or as text: --backend-option algorithm=LD_MMA, memory=10.
#pragma once

namespace contactqp {

struct NloptOptions {
  // The gradient-based NLopt algorithm that maximises θ(λ) over λ ≥ 0 (backend option
  // "algorithm": LD_LBFGS, LD_CCSAQ, LD_MMA, LD_SLSQP).
  enum class Algorithm { Lbfgs, Ccsaq, Mma, Slsqp };
  Algorithm algorithm = Algorithm::Lbfgs;
  int memory = 0;  // L-BFGS: correction pairs kept (backend option "memory"); 0 = NLopt's choice
};

}  // namespace contactqp
