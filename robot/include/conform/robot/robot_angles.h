#pragma once
// Orientation conventions of robot and CNC controllers (docs/export.md), from a rotation matrix whose columns are the
// tool frame's x, y, z axes in the base frame. Angles in degrees, as the controllers take them.
//
// Euler angles are in the controllers' range, (-180, 180] (B in [-90, 90]): across +-180 a value steps by 360 degrees
// while the rotation moves on smoothly (the controllers interpolate the rotation, not the numbers). The others take
// the previous point's value (or nullptr) and return the representation closest to it: no quaternion sign flips and
// no rotation-vector jumps between consecutive points.

#include <Eigen/Core>

namespace conform {

// KUKA A, B, C (and FANUC R, P, W): R = Rz(A) Ry(B) Rx(C), rotations about z, then the new y', then x'' (Z-Y'-X'').
// B in [-90, 90], A and C in (-180, 180]. At gimbal lock (|B| = 90 deg, cos B below 1e-12) only A - C (B = 90) or
// A + C (B = -90) is defined: A keeps its previous value (0 for the first point) and C takes the rest.
Eigen::Vector3d euler_zyx_deg(const Eigen::Matrix3d& rotation, const Eigen::Vector3d* previous);

// Staubli rx, ry, rz: R = Rx(rx) Ry(ry) Rz(rz) (X-Y'-Z''). ry in [-90, 90], rx and rz in (-180, 180] (rx kept at
// lock).
Eigen::Vector3d euler_xyz_deg(const Eigen::Matrix3d& rotation, const Eigen::Vector3d* previous);

// Unit quaternion (w, x, y, z) = (q1, q2, q3, q4) of ABB: w the scalar part. w >= 0 for the first point, then the
// sign closest to `previous`.
Eigen::Vector4d quaternion_wxyz(const Eigen::Matrix3d& rotation, const Eigen::Vector4d* previous);

// Universal Robots rotation vector (rx, ry, rz) = angle * unit axis, rad, angle in [0, pi]; near pi, the equivalent
// vector (angle - 2 pi) * axis when that is closer to `previous`.
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& rotation, const Eigen::Vector3d* previous);

}  // namespace conform
