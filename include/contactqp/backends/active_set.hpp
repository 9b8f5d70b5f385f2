// The options of the active_set backend (solvers/active_set.cpp). Set with
// SolveOptions::set(ActiveSetOptions{...}), or as text: --backend-option max_dense_mb=N.
#pragma once

namespace contactqp {

struct ActiveSetOptions {
  // S = B K⁻¹ Bᵀ (m × m) is formed dense when S and one factorisation of its active block,
  // 16 m² bytes, fit in this limit (m ≤ 8192 at the default 1 GiB). Above it S is applied
  // matrix-free, one solve with K per product, and its active blocks are solved by CG.
  double max_dense_bytes = 1024.0 * 1024.0 * 1024.0;
};

}  // namespace contactqp
