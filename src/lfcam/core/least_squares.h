#pragma once
// Linear least squares and rank, each compiled once here: Eigen's column-pivoting QR and full-
// pivoting LU on dynamic matrices are heavy templates (about 11 s of GCC's -O3 in every file that
// instantiated them; docs/robustness.md, stop 79), and the import, the build and the array's fit
// each did.
#include <Eigen/Core>

namespace lfcam {

// The x minimising |a x - b| (Eigen's ColPivHouseholderQR), one column of b at a time or all.
Eigen::VectorXd SolveLeastSquares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);
Eigen::MatrixXd SolveLeastSquares(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

// The rank of `a` as Eigen's FullPivLU finds it (its default threshold).
int MatrixRank(const Eigen::MatrixXd& a);

}  // namespace lfcam
