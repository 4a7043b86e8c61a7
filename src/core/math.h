// Small vector types and constants. Eigen does the linear algebra; these aliases carry the
// precision in their names: float for radiance and rays, double for geometry and cameras.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace insitu {

using Vec2f = Eigen::Vector2f;
using Vec3f = Eigen::Vector3f;
using Vec4f = Eigen::Vector4f;
using Vec2d = Eigen::Vector2d;
using Vec3d = Eigen::Vector3d;
using Mat3d = Eigen::Matrix3d;
using Mat4d = Eigen::Matrix4d;
using Rgb = Eigen::Array3f;  // linear Rec.709 radiance or reflectance

constexpr double kPi = 3.14159265358979323846;
constexpr float kPiF = 3.14159265358979323846f;

inline double deg_to_rad(double deg) { return deg * kPi / 180.0; }
inline double rad_to_deg(double rad) { return rad * 180.0 / kPi; }

// Luminance of linear Rec.709 (DESIGN.md "Colour and light").
inline float luminance(const Rgb& c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

inline bool all_finite(const Vec3d& v) { return v.allFinite(); }

// The rotation nearest to M in the Frobenius norm: the orthogonal polar factor U Vᵀ of the SVD
// M = U Σ Vᵀ (Higham 1986, "Computing the polar decomposition"). For det M > 0 it is a rotation.
Mat3d nearest_rotation(const Mat3d& M);

}  // namespace insitu
