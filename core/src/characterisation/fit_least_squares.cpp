// Least squares: QR of the equilibrated design in the free coordinates, with its condition number.
#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "fit_problem.hpp"
#include "tristim/error.hpp"

namespace tristim::fit_detail {

// Least squares in the free coordinates; returns z (Q × 3) and the condition number.
Eigen::MatrixXd solve_ls(const Problem& pr, const FitOptions& options, double& cond) {
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(pr.B);
  Eigen::MatrixXd R = qr.matrixQR().topRows(pr.q).triangularView<Eigen::Upper>();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(R);
  const auto& sv = svd.singularValues();
  const double smax = sv(0), smin = sv(sv.size() - 1);
  cond = smin > 0 ? smax / smin : INFINITY;
  if (!(cond <= options.max_condition)) {
    std::ostringstream ss;
    ss << "model '" << pr.info->id << "': the design matrix is singular or nearly so (condition number "
       << cond << " > " << options.max_condition
       << "); collinear camera RGB (e.g. only grey patches) or too many terms for these patches";
    throw Error(ErrorCode::IllConditioned, ss.str());
  }
  return qr.solve(pr.Y - pr.base);
}

}  // namespace tristim::fit_detail
