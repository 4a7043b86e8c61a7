// The variance of a linear combination of least-squares parameters from the fit's normal matrix
// (inverse lighting's σ of a source's added power, of a colour channel).
#pragma once
#include <Eigen/Core>

namespace insitu {

// σ² · gᵀ (JᵀJ)⁺ g: the variance of the linear combination g of the parameters. Infinite when g has
// a part in the null space (the data say nothing about it); a nearly null direction gives a huge
// value by itself. It is computed in units where every parameter's information is 1: with
// D = diag(JᵀJ)^(−½), gᵀ (JᵀJ)⁻¹ g = (D g)ᵀ (D JᵀJ D)⁻¹ (D g), summed over the eigenpairs of the
// scaled matrix, so "null" (an eigenvalue under 10⁻¹⁴ of the largest) does not depend on units. The
// parts' a differ in scale by orders of magnitude (a lamp's 15 texels at the clip level beside a
// window's 600); unscaled, a tied column's large information pushed a lamp's well-determined
// direction under that threshold, and its σ became infinite. A parameter without information (a
// zero diagonal: no pixel sees it) is null.
double variance_along(const Eigen::MatrixXd& jtj, const Eigen::VectorXd& g, double sigma_r);

}  // namespace insitu
