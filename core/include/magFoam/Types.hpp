// Basic numeric types and physical constants shared by every part of magFoam.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <numbers>

namespace mag {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// Vacuum permeability, the exact pre-2019 SI value (docs/physics.md#units-and-conventions), in T m / A.
inline constexpr double mu0 = 4.0e-7 * std::numbers::pi;
inline constexpr double pi = std::numbers::pi;

} // namespace mag
