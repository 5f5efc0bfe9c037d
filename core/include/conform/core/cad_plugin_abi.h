#pragma once
// The C interface between core's reader dispatch (core/src/cad_reader.cpp) and the cad plugin (cad/, the only module
// that links OpenCASCADE; loaded with dlopen on the first .step/.stp/.iges/.igs file, so `conform --help` never loads
// OCCT). Plain C types only: the two sides agree on this header and kConformCadAbiVersion, nothing else.
// Memory in a result is allocated by the plugin and released by its conform_cad_free().

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CONFORM_CAD_ABI_VERSION 3

enum conform_cad_format { CONFORM_CAD_STEP = 1, CONFORM_CAD_IGES = 2 };

enum conform_cad_body_kind {
  CONFORM_CAD_SOLID = 0,        // closed: its faces' orientation is checked (outside positive)
  CONFORM_CAD_OPEN_SHELL = 1,   // a shell outside any solid: the sign follows the faces' orientation in the file
  CONFORM_CAD_FREE_FACES = 2,   // faces outside any shell, gathered into one body
};

// The B-rep surface a face lies on (OpenCASCADE's GeomAbs_SurfaceType).
enum conform_cad_surface {
  CONFORM_CAD_PLANE = 0,
  CONFORM_CAD_CYLINDER = 1,
  CONFORM_CAD_CONE = 2,
  CONFORM_CAD_SPHERE = 3,
  CONFORM_CAD_TORUS = 4,
  CONFORM_CAD_BEZIER = 5,
  CONFORM_CAD_BSPLINE = 6,
  CONFORM_CAD_REVOLUTION = 7,
  CONFORM_CAD_EXTRUSION = 8,
  CONFORM_CAD_OFFSET = 9,
  CONFORM_CAD_OTHER_SURFACE = 10,
};

typedef void (*conform_cad_progress_fn)(void* context, const char* stage, double fraction);

typedef struct conform_cad_request {
  int abi_version;           // CONFORM_CAD_ABI_VERSION
  const char* path;          // the file (already checked by read_input_file: a regular file, not empty)
  const char* bytes;         // its contents
  size_t size;
  int format;                // conform_cad_format
  double deflection_mm;      // chordal deflection of the tessellation, > 0
  double angular_deflection_rad;
  size_t max_triangles;      // refuse a tessellation estimated (before meshing) or found to exceed this, > 0
  conform_cad_progress_fn progress;  // may be NULL
  void* progress_context;
} conform_cad_request;

typedef struct conform_cad_body {
  int kind;                  // conform_cad_body_kind
  size_t faces;              // CAD faces
  size_t triangles;
  size_t failed_faces;       // faces the tessellation gave no triangles
  double box_min_mm[3];      // over its triangulation
  double box_max_mm[3];
  double volume_mm3;         // solids: the tessellation's enclosed volume (> 0 after the orientation check)
  int flipped;               // 1: the solid's faces pointed inwards and were reversed
} conform_cad_body;

// One B-rep face, in the part frame (placements applied), mm. The analytic surfaces' nominal parameters; for the
// others (bezier, bspline, ...) only the fields above `origin_mm`.
typedef struct conform_cad_face {
  int surface;               // conform_cad_surface
  int reversed;              // 1: the face is reversed on its surface in the file (TopAbs_REVERSED)
  // Where outside is, after the face's orientation and a solid's orientation check (flipped): plane +1 (axis is
  // then the outward normal); cylinder, cone, sphere, torus +1 when outside is away from the axis (centre; the
  // torus: its tube's centre circle), a boss or shaft, -1 towards it, a hole or bore; 0 for other surfaces.
  int sense;
  size_t body;               // index into the result's bodies
  size_t triangles;          // its triangles (0: it failed to tessellate)
  double area_mm2;
  double centre_mm[3];       // area centroid of the face
  double origin_mm[3];       // plane: centre_mm; cylinder: the axis point nearest centre_mm; cone: its apex;
                             // sphere, torus: the centre
  double axis[3];            // unit; plane: outward normal; cylinder, torus: the axis; cone: from the apex into the
                             // cone (its radius grows along it); sphere: (0, 0, 1)
  double radius_mm;          // cylinder, sphere; torus: the major radius; cone: 0
  double minor_radius_mm;    // torus
  double half_angle_rad;     // cone, in (0, pi/2)
} conform_cad_face;

typedef struct conform_cad_result {
  char* error;               // NULL on success; otherwise why (without the path), to be freed with the result
  char file_unit[32];        // the file's length unit as written in it ("MM", "M", "INCH", ...)
  double mm_per_file_unit;   // the factor applied to reach millimetres
  double* vertices;          // 3 * vertex_count, mm
  size_t vertex_count;
  int32_t* triangles;        // 3 * triangle_count, counter-clockwise seen from outside
  size_t triangle_count;
  conform_cad_body* bodies;
  size_t body_count;
  char* warnings;            // '\n'-separated sentences, or NULL
  int32_t* triangle_faces;   // triangle_count: the index into faces of the face each triangle came from
  conform_cad_face* faces;   // every face of every body, bodies in order (sum of bodies' faces)
  size_t face_count;
} conform_cad_result;

// Returns 0 on success; otherwise non-zero with result->error set. Never throws. The result must be released with
// conform_cad_free() whatever the return value.
typedef int (*conform_cad_read_fn)(const conform_cad_request* request, conform_cad_result* result);
typedef void (*conform_cad_free_fn)(conform_cad_result* result);

#ifdef __cplusplus
}
#endif
