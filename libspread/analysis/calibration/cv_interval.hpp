#pragma once
// How well a CV measured on a few trays pins the CV of the bout (docs/field-calibration.md, "Quick
// check").
//
// Taking the n trays as a sample of the bout's distribution (normal), McKay's interval for the
// population CV κ from the sample CV K with ν = n − 1 degrees of freedom is (Vangel 1996, Eq. 4):
//     κ_low  = K / sqrt((u₁/(ν+1) − 1) K² + u₁/ν),   u₁ = χ²_ν quantile at 1 − α/2,
//     κ_high = K / sqrt((u₂/(ν+1) − 1) K² + u₂/ν),   u₂ = χ²_ν quantile at α/2,
// κ_high = +infinity when its radicand is not positive (K too large for so few trays to bound it).
// For a small K it is K · sqrt(ν / u): the spread of the sample standard deviation, with (n − 1) s²/σ²
// ~ χ²_ν. With 4 trays (ν = 3) the 95 % interval of a CV of 10 % is 5.7 to 40 %.
#include <limits>

namespace spread::calibration {

// Quantile of the χ² distribution with `dof` degrees of freedom (dof >= 1) at probability p in (0, 1):
// P(dof/2, x/2) = p by bisection on the regularised lower incomplete gamma function (its series), to a
// relative 1e-10. Throws std::invalid_argument for arguments out of range.
double chi_square_quantile(double p, int dof);

struct CvInterval {
  double low = 0.0;                                        // fraction
  double high = std::numeric_limits<double>::infinity();   // fraction; +inf: unbounded
  double confidence = 0.95;
  int trays = 0;
};

// McKay's interval for a sample CV `cv` (fraction, >= 0) from `trays` >= 2 values. Throws
// std::invalid_argument for a confidence outside (0, 1), fewer than 2 trays or a negative CV.
CvInterval cv_interval(double cv, int trays, double confidence = 0.95);

}  // namespace spread::calibration
