// The norms and relative measures every layer uses (the certificate, the backends' stopping
// tests, compare, benchmarks, tests): one definition each, so "relative difference" means the
// same thing in a table, a test and a stopping rule.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace contactqp {

// max |v_i|, and 0 for an empty vector (a QP without constraints has an empty λ).
double inf_norm(const Eigen::VectorXd& v);

// max_i Σ_j |A_ij|, which bounds a symmetric A's largest eigenvalue; 0 for an empty A.
double infinity_norm(const Eigen::SparseMatrix<double>& A);

// x / scale, or x itself when scale is not positive (a residual of a problem whose data are all 0).
double relative(double x, double scale);

// |a − b| / |b|, with b the reference (an analytic value); the absolute difference when b = 0.
double relative_error(double a, double b);

// ‖a − b‖₂ / ‖b‖₂, with b the reference; the absolute difference when b = 0.
double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

// ‖a − b‖∞ / ‖b‖∞, with b the reference; the absolute difference when b = 0.
double relative_difference_inf(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

// ‖a − b‖₂ / max(‖a‖₂, ‖b‖₂), symmetric for pairwise checks where neither side is the
// reference; 0 when both are 0.
double symmetric_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

}  // namespace contactqp
