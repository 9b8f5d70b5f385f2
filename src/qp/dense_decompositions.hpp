#pragma once
// Eigen's Jacobi SVD and symmetric eigensolver on dynamic matrices, compiled once for the whole
// build (dense_decompositions.cpp) instead of in every file that uses them. Each costs about
// 10 s of g++ -O3 per file that instantiates it, and CI compiles the tree twice from empty
// directories (tools/run-tests.sh). Include this header instead of <Eigen/SVD> and
// <Eigen/Eigenvalues> when you use Eigen::JacobiSVD<Eigen::MatrixXd> or
// Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>: a file that includes Eigen's headers directly
// still compiles and links, only slower. Only a compute() on an Eigen::MatrixXd itself is
// shared; one on an expression (a product, a block) is compiled where it is written.
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

extern template class Eigen::JacobiSVD<Eigen::MatrixXd>;
extern template class Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;
extern template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>&
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(const Eigen::EigenBase<Eigen::MatrixXd>&, int);
