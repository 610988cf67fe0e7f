// How far off a fitted pose may be: the 99 % quantile of its rotation and translation errors'
// norms under the fit's Gaussian covariance. What the estimator compares with its ok limits.
#pragma once

#include <Eigen/Core>

namespace rovctl::estimator {

// The 99 % quantile of |e| for e ~ N(0, C), C 3 x 3 symmetric positive semi-definite: |e|^2 is
// a weighted sum of chi-square(1) terms, taken as Satterthwaite's scaled chi-square with
// Wilson and Hilferty's quantile. 2.58 sqrt(c) when one axis carries all the variance c, 3.37
// sqrt(c / 3) when three carry it alike; 0 for C = 0; NaN when C is not finite.
double norm_quantile_99(const Eigen::Matrix3d& C);

struct ErrorBound {
  double m = 0.0;    // translation
  double deg = 0.0;  // rotation angle
};

// Of a pose covariance ordered rotation vector (rad), then translation (m).
ErrorBound error_bound_99(const Eigen::Matrix<double, 6, 6>& covariance);

// 3 sqrt(trace) of each block: 1.17 (one long axis) to 1.54 (three equal axes) times the 99 %
// quantile. For fits whose covariance is known to understate their bias.
ErrorBound error_bound_3_sigma(const Eigen::Matrix<double, 6, 6>& covariance);

// Whether another fit of the same data explains it as well as the chosen one, given each fit's
// residual sum of squares over independent residuals in units of the noise variance: the other's
// exceeds the chosen's by less than chi-square(1)'s 99 % quantile (a likelihood-ratio test of one
// discrete alternative). A pose the data cannot tell from another 30 deg away is not known to
// better than 30 deg, whatever its own covariance says.
bool fits_as_well(double chi2, double other_chi2);

}  // namespace rovctl::estimator
