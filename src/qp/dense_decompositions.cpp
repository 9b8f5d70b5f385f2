// The one instantiation of the decompositions dense_decompositions.hpp declares (see there why).
// Kept out of unity batches (CMakeLists.txt): a batch-mate that included the header after
// these definitions would declare them after they are defined.
#include "qp/dense_decompositions.hpp"

template class Eigen::JacobiSVD<Eigen::MatrixXd>;
template class Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;
template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>&
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(const Eigen::EigenBase<Eigen::MatrixXd>&, int);
