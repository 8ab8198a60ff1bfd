#include "lfcam/core/least_squares.h"

#include <Eigen/LU>
#include <Eigen/QR>

namespace lfcam {

Eigen::VectorXd SolveLeastSquares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return a.colPivHouseholderQr().solve(b);
}

Eigen::MatrixXd SolveLeastSquares(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.colPivHouseholderQr().solve(b);
}

int MatrixRank(const Eigen::MatrixXd& a) {
  return int(Eigen::FullPivLU<Eigen::MatrixXd>(a).rank());
}

}  // namespace lfcam
