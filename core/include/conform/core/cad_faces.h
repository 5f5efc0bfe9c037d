#pragma once
// A CAD reference face by face (issue 33): the tessellation read_cad() returns, with, for every triangle, the B-rep
// face it came from and, for every face, its surface type and, for analytic surfaces (plane, cylinder, cone, sphere,
// torus), the nominal parameters in mm in the part frame and which side is outside. Read through the same isolated
// child process as read_cad() (core/src/cad_child.h); what the child sends is checked as untrusted input.
//
//   CadFaces cad = read_cad_faces("part.step", CadReadOptions{}, &report, &warnings);
//   const CadFace& f = cad.faces[cad.triangle_face[t]];        // the face of triangle t
//   const double d = analytic_signed_distance(f, p);            // + outside, to the exact surface

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cad.h"
#include "conform/core/mesh.h"

namespace conform {

enum class CadSurfaceType { kPlane, kCylinder, kCone, kSphere, kTorus, kBezier, kBSpline, kRevolution, kExtrusion,
                            kOffset, kOther };
// "plane", "cylinder", "cone", "sphere", "torus", "bezier", "bspline", "revolution", "extrusion", "offset", "other".
const char* to_string(CadSurfaceType type);
// Plane, cylinder, cone, sphere, torus: the surfaces with nominal parameters below.
bool is_analytic(CadSurfaceType type);

struct CadFace {
  CadSurfaceType type = CadSurfaceType::kOther;
  bool reversed = false;    // reversed on its surface in the file (TopAbs_REVERSED)
  // Analytic surfaces: plane +1 (`axis` is its outward normal); cylinder, cone, sphere, torus +1 when outside is away
  // from the axis or centre (a boss, a shaft), -1 towards it (a hole, a bore). 0 for the other surfaces.
  int sense = 0;
  std::size_t body = 0;       // index into CadReport::bodies
  std::size_t triangles = 0;  // in the welded mesh
  double area_mm2 = 0.0;
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  // area centroid of the face
  // plane: centre_mm; cylinder: the axis point nearest centre_mm; cone: its apex; sphere, torus: the centre.
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();
  // Unit. plane: outward normal; cylinder, torus: axis; cone: from the apex into the cone; sphere: z.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius_mm = 0.0;        // cylinder, sphere; torus: major radius
  double minor_radius_mm = 0.0;  // torus
  double half_angle_rad = 0.0;   // cone
};

// The signed distance of p from the face's (untrimmed) analytic surface, mm, + outside; NaN for other surfaces. The
// cone: the distance to its nappe's generator through p's half-plane (exact on the side away from the apex).
double analytic_signed_distance(const CadFace& face, const Eigen::Vector3d& p);
// The outward unit normal of the analytic surface nearest p (the gradient of the distance); NaN for other surfaces
// and on the axis of a surface of revolution.
Eigen::Vector3d analytic_outward_normal(const CadFace& face, const Eigen::Vector3d& p);

struct CadFaces {
  Mesh mesh;                                // as read_cad() returns it: welded, mm, outside positive
  std::vector<std::int32_t> triangle_face;  // per triangle of mesh, the index into faces
  std::vector<CadFace> faces;               // every face of every body, in the file's order (failed ones too)
};

// read_cad() with the faces. Throws conform::Error as read_cad() does, and when the reader's face data do not add up.
CadFaces read_cad_faces(const std::string& path, const CadReadOptions& options, CadReport* report,
                        std::vector<std::string>* warnings);

}  // namespace conform
