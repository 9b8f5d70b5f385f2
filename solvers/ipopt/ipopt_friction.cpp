// The ipopt backend's dual NLP of Tresca's problem (ipopt_friction.hpp); built with Ipopt only.
#include <IpIpoptApplication.hpp>

#include <algorithm>
#include <vector>

#include "ipopt_friction.hpp"

namespace contactqp::detail {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// x = (u [n], λ_N [m], λ_T [m·nd]); constraints: the n equalities, then one disc per node with
// r_i > 0 (3D only).
class FrictionDualNlp : public ContactNlp {
 public:
  FrictionDualNlp(const QuadraticProgram& qp, const VectorXd& radii)
      : qp_(qp),
        radii_(radii),
        n_(qp.n_dofs()),
        m_(qp.n_constraints()),
        nd_(qp.friction.n_directions),
        K_lower_(qp.K.triangularView<Eigen::Lower>()) {
    // [K Bᵀ Tᵀ], the equalities' Jacobian, column-major over x.
    std::vector<Eigen::Triplet<double>> entries;
    auto append = [&entries](const SparseMatrix& A, int column_offset) {
      for (int j = 0; j < A.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(A, j); it; ++it)
          entries.emplace_back(static_cast<int>(it.row()), column_offset + j, it.value());
    };
    append(qp.K, 0);
    append(SparseMatrix(qp.B.transpose()), n_);
    append(SparseMatrix(qp.friction.T.transpose()), n_ + m_);
    equalities_.resize(n_, n_ + m_ + m_ * nd_);
    equalities_.setFromTriplets(entries.begin(), entries.end());
    if (nd_ == 2)
      for (int i = 0; i < m_; ++i)
        if (radii_[i] > 0) discs_.push_back(i);
    n_inequalities = m_ + static_cast<int>(discs_.size()) + (nd_ == 1 ? 2 * m_ : 0);
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = n_ + m_ + m_ * nd_;
    m = n_ + static_cast<Index>(discs_.size());
    nnz_jac_g = static_cast<Index>(equalities_.nonZeros() + 2 * discs_.size());
    nnz_h_lag = static_cast<Index>(K_lower_.nonZeros() + 2 * discs_.size());
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    std::fill(x_l, x_l + n, -kNoBound);
    std::fill(x_u, x_u + n, kNoBound);
    std::fill(x_l + n_, x_l + n_ + m_, 0.0);  // λ_N ≥ 0
    for (int i = 0; i < m_; ++i)
      for (int k = 0; k < nd_; ++k) {
        const int j = n_ + m_ + i * nd_ + k;
        if (!(radii_[i] > 0)) {
          x_l[j] = x_u[j] = 0;  // no friction force at this node
        } else if (nd_ == 1) {
          x_l[j] = -radii_[i];
          x_u[j] = radii_[i];
        }
      }
    std::copy(qp_.f.data(), qp_.f.data() + n_, g_l);
    std::copy(qp_.f.data(), qp_.f.data() + n_, g_u);
    for (size_t d = 0; d < discs_.size(); ++d) {
      g_l[n_ + d] = -kNoBound;
      g_u[n_ + d] = radii_[discs_[d]];
    }
    return true;
  }

  bool get_constraints_linearity(Index m, LinearityType* types) override {
    std::fill(types, types + m, LINEAR);
    std::fill(types + n_, types + m, NON_LINEAR);
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*, Index, bool init_lambda,
                          Number*) override {
    if (init_x) std::fill(x, x + n, 0.0);
    return !init_z && !init_lambda;
  }

  bool eval_f(Index, const Number* x, bool, Number& value) override {
    const Eigen::Map<const VectorXd> u(x, n_), lambda(x + n_, m_), lambda_t(x + n_ + m_, m_ * nd_);
    value = 0.5 * u.dot(qp_.K * u) + qp_.g.dot(lambda) + qp_.friction.offset.dot(lambda_t);
    return true;
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* gradient) override {
    const Eigen::Map<const VectorXd> u(x, n_);
    Eigen::Map<VectorXd>(gradient, n_) = qp_.K * u;
    Eigen::Map<VectorXd>(gradient + n_, m_) = qp_.g;
    Eigen::Map<VectorXd>(gradient + n_ + m_, m_ * nd_) = qp_.friction.offset;
    return true;
  }

  bool eval_g(Index n, const Number* x, bool, Index, Number* g) override {
    Eigen::Map<VectorXd>(g, n_) = equalities_ * Eigen::Map<const VectorXd>(x, n);
    for (size_t d = 0; d < discs_.size(); ++d) {
      const int i = discs_[d];
      const Number* y = x + n_ + m_ + i * nd_;
      g[n_ + d] = (y[0] * y[0] + y[1] * y[1]) / radii_[i];
    }
    return true;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* rows, Index* cols, Number* values) override {
    Index k = copy_entries(equalities_, rows, cols, values, 1.0);
    for (size_t d = 0; d < discs_.size(); ++d)
      for (int c = 0; c < 2; ++c, ++k) {
        const int i = discs_[d], j = n_ + m_ + i * nd_ + c;
        if (values) {
          values[k] = 2 * x[j] / radii_[i];
        } else {
          rows[k] = static_cast<Index>(n_ + d);
          cols[k] = j;
        }
      }
    return true;
  }

  // σ K on u, and 2ν_d/r_i on each disc's two variables.
  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number* multipliers, bool, Index, Index* rows,
              Index* cols, Number* values) override {
    Index k = copy_entries(K_lower_, rows, cols, values, obj_factor);
    for (size_t d = 0; d < discs_.size(); ++d)
      for (int c = 0; c < 2; ++c, ++k) {
        const int i = discs_[d], j = n_ + m_ + i * nd_ + c;
        if (values) {
          values[k] = 2 * multipliers[n_ + d] / radii_[i];
        } else {
          rows[k] = cols[k] = j;
        }
      }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    u = Eigen::Map<const VectorXd>(x, n_);
    lambda = Eigen::Map<const VectorXd>(x + n_, m_).cwiseMax(0.0);
    lambda_t = Eigen::Map<const VectorXd>(x + n_ + m_, m_ * nd_);
    has_solution = true;
  }

 private:
  const QuadraticProgram& qp_;
  const VectorXd radii_;
  const int n_, m_, nd_;
  const SparseMatrix K_lower_;
  SparseMatrix equalities_;  // n × (n + m + m·nd): [K Bᵀ Tᵀ]
  std::vector<int> discs_;   // nodes with a disc constraint (3D, r_i > 0)
};

}  // namespace

Index copy_entries(const SparseMatrix& A, Index* rows, Index* cols, Number* values, double factor) {
  Index k = 0;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it, ++k) {
      if (values) {
        values[k] = factor * it.value();
      } else {
        rows[k] = static_cast<Index>(it.row());
        cols[k] = static_cast<Index>(it.col());
      }
    }
  return k;
}

Ipopt::SmartPtr<ContactNlp> make_friction_dual_nlp(const QuadraticProgram& qp, const VectorXd& radii) {
  return new FrictionDualNlp(qp, radii);
}

}  // namespace contactqp::detail
