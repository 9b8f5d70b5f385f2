#include "friction_qps.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace contactqp::testing {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd random_spd(int n, std::mt19937& random) {
  std::normal_distribution<double> normal;
  MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = normal(random);
  return A * A.transpose() + 0.5 * n * MatrixXd::Identity(n, n);
}

VectorXd random_unit(int size, std::mt19937& random) {
  std::normal_distribution<double> normal;
  VectorXd v(size);
  for (int k = 0; k < size; ++k) v[k] = normal(random);
  return v / v.norm();
}

}  // namespace

QuadraticProgram node_on_plane(const VectorXd& k_t, double k_n, const VectorXd& q, double P, double gap,
                               FrictionLaw law, double value) {
  const int nd = static_cast<int>(k_t.size()), n = nd + 1;
  VectorXd diagonal(n), f(n);
  diagonal << k_t, k_n;
  f << q, -P;
  MatrixXd B = MatrixXd::Zero(1, n), T = MatrixXd::Zero(nd, n);
  B(0, nd) = -1;
  for (int k = 0; k < nd; ++k) T(k, k) = 1;
  QuadraticProgram qp;
  qp.K = MatrixXd(diagonal.asDiagonal()).sparseView();
  qp.f = f;
  qp.B = B.sparseView();
  qp.g = VectorXd::Constant(1, gap);
  qp.friction.law = law;
  qp.friction.n_directions = nd;
  qp.friction.T = T.sparseView();
  qp.friction.offset = VectorXd::Zero(nd);
  (law == FrictionLaw::Tresca ? qp.friction.threshold : qp.friction.coefficient) = VectorXd::Constant(1, value);
  return qp;
}

FrictionSolution node_on_plane_solution(const VectorXd& k_t, double k_n, const VectorXd& q, double P, double gap,
                                        FrictionLaw law, double value) {
  const int nd = static_cast<int>(k_t.size());
  FrictionSolution s;
  s.u = VectorXd::Zero(nd + 1);
  const double lambda_n = std::max(0.0, P - k_n * gap);
  s.u[nd] = lambda_n > 0 ? -gap : -P / k_n;
  s.lambda = VectorXd::Constant(1, lambda_n);
  const double r = law == FrictionLaw::Tresca ? value : value * lambda_n;
  if (q.norm() <= r) {
    s.lambda_t = q;  // stick: u_t = 0
    return s;
  }
  // Slip: the root ρ of φ(ρ) = Σ (q_k/(k_k ρ + r))² − 1, decreasing from φ(0) = ‖q‖²/r² − 1 > 0.
  auto phi = [&](double rho) {
    double sum = 0;
    for (int k = 0; k < nd; ++k) sum += std::pow(q[k] / (k_t[k] * rho + r), 2);
    return sum - 1;
  };
  double low = 0, high = q.norm() / k_t.minCoeff();
  for (int it = 0; it < 200; ++it) (phi(0.5 * (low + high)) > 0 ? low : high) = 0.5 * (low + high);
  const double rho = 0.5 * (low + high);
  for (int k = 0; k < nd; ++k) s.u[k] = rho * q[k] / (k_t[k] * rho + r);
  s.lambda_t = r * s.u.head(nd) / rho;
  return s;
}

QuadraticProgram random_tresca_2d(int n, int m, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const MatrixXd K = random_spd(n, random);
  VectorXd f(n);
  for (int i = 0; i < n; ++i) f[i] = normal(random);
  MatrixXd B(m, n), T(m, n);
  for (int i = 0; i < m; ++i) {
    B.row(i) = random_unit(n, random).transpose();
    VectorXd t = random_unit(n, random);
    t -= t.dot(B.row(i).transpose()) * B.row(i).transpose();  // tangent ⊥ normal, as on a mesh
    T.row(i) = t.normalized().transpose();
  }
  const VectorXd free_optimum = K.ldlt().solve(f);
  VectorXd g = B * free_optimum, offset = T * free_optimum, threshold(m);
  for (int i = 0; i < m; ++i) {
    g[i] += (i % 2 == 0 ? -0.5 : 0.5) * std::abs(normal(random));
    offset[i] += 0.3 * normal(random);
    threshold[i] = 0.05 + 0.3 * uniform(random);
  }
  QuadraticProgram qp;
  qp.K = K.sparseView();
  qp.f = f;
  qp.B = B.sparseView();
  qp.g = g;
  qp.friction.law = FrictionLaw::Tresca;
  qp.friction.n_directions = 1;
  qp.friction.T = T.sparseView();
  qp.friction.offset = offset;
  qp.friction.threshold = threshold;
  return qp;
}

FrictionSolution tresca_by_enumeration(const QuadraticProgram& qp) {
  const int n = qp.n_dofs(), m = qp.n_constraints();
  if (m > 5 || qp.friction.n_directions != 1) throw std::invalid_argument("tresca_by_enumeration: 2D, m ≤ 5");
  const MatrixXd K(qp.K), B(qp.B), T(qp.friction.T);
  const VectorXd& s = qp.friction.threshold;
  const VectorXd& offset = qp.friction.offset;
  int combinations = 1;
  for (int i = 0; i < m; ++i) combinations *= 6;
  for (int code = 0; code < combinations; ++code) {
    // Row i: contact = digit % 2, tangential state = digit / 2 (0 stick, 1 slip at +s, 2 at −s).
    std::vector<int> contact(m), state(m);
    for (int i = 0, c = code; i < m; ++i, c /= 6) {
      contact[i] = (c % 6) % 2;
      state[i] = (c % 6) / 2;
    }
    std::vector<int> rows_n, rows_t;
    VectorXd rhs_u = qp.f;
    for (int i = 0; i < m; ++i) {
      if (contact[i]) rows_n.push_back(i);
      if (state[i] == 0)
        rows_t.push_back(i);
      else
        rhs_u -= (state[i] == 1 ? s[i] : -s[i]) * T.row(i).transpose();
    }
    const int a = static_cast<int>(rows_n.size()), b = static_cast<int>(rows_t.size());
    MatrixXd kkt = MatrixXd::Zero(n + a + b, n + a + b);
    VectorXd rhs(n + a + b);
    kkt.topLeftCorner(n, n) = K;
    rhs.head(n) = rhs_u;
    for (int k = 0; k < a; ++k) {
      kkt.block(0, n + k, n, 1) = B.row(rows_n[k]).transpose();
      kkt.block(n + k, 0, 1, n) = B.row(rows_n[k]);
      rhs[n + k] = qp.g[rows_n[k]];
    }
    for (int k = 0; k < b; ++k) {
      kkt.block(0, n + a + k, n, 1) = T.row(rows_t[k]).transpose();
      kkt.block(n + a + k, 0, 1, n) = T.row(rows_t[k]);
      rhs[n + a + k] = offset[rows_t[k]];
    }
    Eigen::FullPivLU<MatrixXd> lu(kkt);
    if (lu.rank() < n + a + b) continue;
    const VectorXd z = lu.solve(rhs);
    FrictionSolution candidate{z.head(n), VectorXd::Zero(m), VectorXd::Zero(m)};
    for (int k = 0; k < a; ++k) candidate.lambda[rows_n[k]] = z[n + k];
    for (int i = 0; i < m; ++i)
      if (state[i] != 0) candidate.lambda_t[i] = state[i] == 1 ? s[i] : -s[i];
    for (int k = 0; k < b; ++k) candidate.lambda_t[rows_t[k]] = z[n + a + k];
    const double eps = 1e-11 * (1 + z.cwiseAbs().maxCoeff() + qp.g.cwiseAbs().maxCoeff());
    const VectorXd slip = T * candidate.u - offset;
    bool feasible = (B * candidate.u - qp.g).maxCoeff() <= eps && candidate.lambda.minCoeff() >= -eps;
    for (int i = 0; i < m && feasible; ++i) {
      if (state[i] == 0) feasible = std::abs(candidate.lambda_t[i]) <= s[i] + eps;
      if (state[i] == 1) feasible = slip[i] >= -eps;
      if (state[i] == 2) feasible = slip[i] <= eps;
    }
    if (feasible) {
      candidate.lambda = candidate.lambda.cwiseMax(0.0);
      return candidate;
    }
  }
  throw std::runtime_error("tresca_by_enumeration: no KKT point");
}

KnownFrictionQp known_friction_qp(int nodes, int n_directions, FrictionLaw law, unsigned seed, double mu) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.5, 1.5);
  const int nd = n_directions, per_node = nd + 1, n = nodes * per_node;
  const MatrixXd K = random_spd(n, random);
  MatrixXd B = MatrixXd::Zero(nodes, n), T = MatrixXd::Zero(nodes * nd, n);
  VectorXd u(n);
  for (int j = 0; j < n; ++j) u[j] = normal(random);
  VectorXd g(nodes), lambda = VectorXd::Zero(nodes), lambda_t = VectorXd::Zero(nodes * nd), offset(nodes * nd);
  VectorXd threshold(nodes);
  for (int i = 0; i < nodes; ++i) {
    const int normal_dof = i * per_node + nd;
    B(i, normal_dof) = -1;
    for (int k = 0; k < nd; ++k) T(i * nd + k, i * per_node + k) = 1;
    // Pattern: contact + stick, contact + slip, gap + slip, gap + stick.
    const bool contact = i % 4 < 2, slips = i % 4 == 1 || i % 4 == 2;
    g[i] = -u[normal_dof] + (contact ? 0.0 : uniform(random));
    if (contact) lambda[i] = uniform(random);
    threshold[i] = law == FrictionLaw::Tresca ? uniform(random) : mu * lambda[i];
    const VectorXd tangential = u.segment(i * per_node, nd);
    const VectorXd d = random_unit(nd, random);
    if (!(threshold[i] > 0)) {
      offset.segment(i * nd, nd) = tangential - uniform(random) * d;  // no friction force: any slip
    } else if (slips) {
      offset.segment(i * nd, nd) = tangential - uniform(random) * d;  // slip along d ...
      lambda_t.segment(i * nd, nd) = threshold[i] * d;                // ... with λ_T on the rim, along it
    } else {
      offset.segment(i * nd, nd) = tangential;                // no slip ...
      lambda_t.segment(i * nd, nd) = 0.5 * threshold[i] * d;  // ... with λ_T inside the disc
    }
  }
  KnownFrictionQp known;
  QuadraticProgram& qp = known.qp;
  qp.K = K.sparseView();
  qp.f = K * u + B.transpose() * lambda + T.transpose() * lambda_t;
  qp.B = B.sparseView();
  qp.g = g;
  qp.friction.law = law;
  qp.friction.n_directions = nd;
  qp.friction.T = T.sparseView();
  qp.friction.offset = offset;
  if (law == FrictionLaw::Tresca)
    qp.friction.threshold = threshold;
  else
    qp.friction.coefficient = VectorXd::Constant(nodes, mu);
  known.exact = {u, lambda, lambda_t};
  return known;
}

Eigen::SparseMatrix<double> tangents_of(const Eigen::SparseMatrix<double>& B, int dim) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = B;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < rows.rows(); ++i) {
    std::vector<int> cols;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, i); it; ++it) {
      normal[static_cast<int>(cols.size())] = -it.value();
      cols.push_back(static_cast<int>(it.col()));
    }
    if (static_cast<int>(cols.size()) != dim) throw std::invalid_argument("tangents_of: a row of B is not one node's");
    Eigen::Vector3d t1, t2;
    if (dim == 2) {
      t1 = Eigen::Vector3d(normal[1], -normal[0], 0);
    } else {
      int axis = 0;  // the axis least aligned with n
      normal.cwiseAbs().minCoeff(&axis);
      t1 = Eigen::Vector3d::Unit(axis).cross(normal).normalized();
      t2 = normal.cross(t1).normalized();
    }
    for (int c = 0; c < dim; ++c) {
      entries.emplace_back((dim - 1) * i, cols[c], t1[c]);
      if (dim == 3) entries.emplace_back(2 * i + 1, cols[c], t2[c]);
    }
  }
  Eigen::SparseMatrix<double> T((dim - 1) * B.rows(), B.cols());
  T.setFromTriplets(entries.begin(), entries.end());
  return T;
}

}  // namespace contactqp::testing
