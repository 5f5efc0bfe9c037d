#pragma once
// The deformed shape of a ship profile (bulb flat, flat bar, ...) for `generate profile`: the ground-truth map from
// the straight, flat profile's design coordinates (Tx across the web from the measured edge, Ty along the edge from
// the origin; mm) to 3D, and its inverse (straightening).
//
// Flat profile frame: the edge runs along +x from the origin, the web lies towards +y (Tx), its normal is +z.
// Deformed, the edge is a curve E(s) parametrised by its arc length s (the edge neither stretches nor shrinks), with
// the frame R(s) = Rz(theta(s)) Ry(-phi(s)) Rx(psi(s)): tangent T = R e_x, across the web N = R e_y, web normal
// B = R e_z, and the cross-section stays rigid (the assumption of Chen et al.):
//
//   map(Tx, Ty) = E(Ty) + Tx N(Ty),      E(s) = integral_0^s T(sigma) d sigma
//
//   in-plane bow   theta = asin(v'(s)), v(s) = bow_in 4u(1 - u)(1 + a (2u - 1)), u = s / L: the edge's offset across
//                  the web is v(s) exactly (without out-of-plane bow); a != 0 makes the bow a true cubic
//   out-of-plane   phi = asin(w'(s)),   w(s) = bow_out 4u(1 - u): the offset along the web normal
//   twist          psi = twist u, about the edge
//   kink           theta += kink * smootherstep((s - kink_at) / kink_length + 1/2): a local bend of the edge in the
//                  web plane, spread over kink_length

#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct ProfileDeformationOptions {
  double length_mm = 12000.0;        // L (> 0)
  double width_mm = 370.0;           // web width (> 0): Tx in [0, width] lies on the web
  double bow_in_plane_mm = 40.0;     // v at the middle, across the web (signed)
  double bow_asymmetry = 0.0;        // a in [-1, 1]
  double bow_out_of_plane_mm = 0.0;  // w at the middle, along the web normal (signed)
  double twist_rad = 0.0;            // about the edge, from one end to the other (signed)
  double kink_rad = 0.0;             // in-plane bend of the kink (signed; 0: none)
  double kink_at_mm = 4800.0;        // Ty of the kink's middle, in [0, L] (checked only with a kink)
  double kink_length_mm = 100.0;     // over which it bends (> 0)

  bool IsValid(std::string* error) const;
};

class ProfileDeformation {
 public:
  // Throws conform::Error when the options are invalid.
  explicit ProfileDeformation(const ProfileDeformationOptions& options);

  const ProfileDeformationOptions& options() const { return options_; }
  // s is clamped into [0, L].
  Eigen::Vector3d edge(double s_mm) const;
  // Columns T, N, B at s.
  Eigen::Matrix3d frame(double s_mm) const;
  // The ground truth: where design point (Tx, Ty) lies on the deformed profile.
  Eigen::Vector3d map(double tx_mm, double ty_mm) const;
  // The inverse: the design point (Tx, Ty) of a 3D point near the deformed web, and its distance off the web along B
  // (signed). Ty is where (p - E(s)) . T(s) = 0, searched in [0, L].
  Eigen::Vector2d straighten(const Eigen::Vector3d& p, double* off_web_mm = nullptr) const;

 private:
  double heading(double s) const;
  double pitch(double s) const;

  ProfileDeformationOptions options_;
  double step_ = 10.0;
  std::vector<Eigen::Vector3d> table_;  // E(k step)
};

}  // namespace conform
