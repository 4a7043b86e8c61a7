// The extra-sum-of-squares F-test for nested least-squares models (e.g. Seber & Wild, Nonlinear
// Regression, 1989, §5.3): with RSS_1 of the smaller model (k1 parameters) and RSS_2 of the larger
// (k2), from m residuals,
//   F = ((RSS_1 − RSS_2)/(k2 − k1)) / (RSS_2/(m − k2))  ~  F(k2 − k1, m − k2)
// when the smaller model is true and the errors are Gaussian with one unknown σ.
#pragma once

namespace insitu {

// The regularized incomplete beta function I_x(a, b), by its continued fraction (modified
// Lentz's method, Numerical Recipes §6.4), using the symmetry I_x(a,b) = 1 − I_{1−x}(b,a) where the
// fraction converges slowly.
double regularized_incomplete_beta(double a, double b, double x);

// P(F > f) for F ~ F(d1, d2):  I_{d2/(d2 + d1 f)}(d2/2, d1/2).
double f_distribution_sf(double f, double d1, double d2);

}  // namespace insitu
