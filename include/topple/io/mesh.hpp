#pragma once
// Reading a closed triangle mesh (a 3-D scan) for topple/bodies/body.hpp, in double precision.
//
// Formats, chosen by the file's extension (any case): Wavefront OBJ (.obj), OFF (.off, ASCII), STL (.stl, ASCII and
// binary) and PLY (.ply, ASCII, binary little- and big-endian), read by CGAL's own I/O (CGAL::IO::read_OBJ, read_OFF,
// read_STL, read_PLY) into double-precision points and polygons. Before them, a validating pre-scan per format
// (issue 31) checks what those readers assume or guess, so that every refusal names the file, the line (text formats)
// and the field: PLY header grammar, element counts bounded by the bytes the file holds (before anything is
// allocated), the body against the header (absent elements, trailing data, each value a whole token of its type);
// OBJ v lines (x y z, x y z w with w = 1, or x y z r g b, each a whole finite number) and f tokens; the ASCII STL
// grammar (three vertices a facet) and a binary STL's exact size; OFF line by line. Coordinates are quoted as typed.
// Any other extension is refused; a file whose content is not of its extension's format is refused. An OBJ's mtllib
// is never opened.
//
// Recentring: before any arithmetic, the coordinates are measured from the centre of the bounding box of the vertices
// the faces use (in the file's units: x - o is then exact for any mesh lying at least half its size from a coordinate
// plane, e.g. a georeferenced scan at x = 500000 m, y = 4.2e6 m), then scaled by `unit_m`; the file's coordinates of
// that origin are kept in TriangleMesh::origin_m. The bounding-box centre, not the centroid of the vertices: it does
// not depend on how densely a part of the scan is sampled or on a sum's order. A file coordinate beyond 1e8 m is
// refused; the mesh's size is limited as check_mesh says (1 mm to 1 km).
//
// Welding and polygons: vertices with bitwise-equal coordinates are welded into the first of them in the file (an STL
// repeats each vertex in every facet; OBJ and PLY writers split vertices at texture seams); nothing is snapped within a
// tolerance. Polygons are split into fans (a polygon that is not convex is refused). A vertex no face uses takes no
// part (it is given the place of a used one); the numbering of the others is kept.
//
// Messages number vertices and faces as the file does: OBJ vertex numbers as its v lines count them (from 1) and the
// n-th f line as "face n at line L (f a b c)"; OFF and PLY the n-th vertex with the index the faces write (from 0)
// and the n-th face (with its line in a text file); STL the n-th facet (and its line) and its corners' coordinates. A file with vertices but no faces (a point cloud) is refused
// with what to do (mesh it first); an open mesh with its first boundary edge and how to close it.
//
// Units: the file's numbers are multiplied by `unit_m` (1 for metres, 0.001 for millimetres) and read as x east,
// y north, z up. The mesh is then checked (check_mesh in topple/bodies/body.hpp); every refusal is an InputError naming
// the file.
#include <cstdint>
#include <string>
#include <string_view>

#include "topple/bodies/body.hpp"

namespace topple::io {

/// Largest mesh file read: 1 GiB (a binary STL of MeshLimits::max_triangles is 500 MB).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 30;

/// The length of one unit of the file's coordinates, m, from a unit ("m", "cm", "mm" or any length unit that
/// parse_length_m knows, e.g. "in"), a length ("2cm": one unit is 2 cm) or a bare number of metres ("0.001").
/// Throws InputError naming `field` and quoting `unit` otherwise (zero, negative, non-finite, unknown).
[[nodiscard]] double mesh_unit_m(const std::string& unit, const std::string& field);

/// Reads `path` (OBJ, OFF, STL, PLY), recentres it (origin_m), scales it by `unit_m` and checks it (check_mesh).
/// Throws InputError naming the file.
[[nodiscard]] TriangleMesh read_mesh(const std::string& path, double unit_m = 1.0);

/// A mesh file's planar body at options.azimuth_deg: check_body_options, then read_mesh (scaled by `unit_m`), then
/// mesh_body (its positions moved to the file's coordinates: to_file_coordinates). Throws InputError naming the mesh file, or the option that is wrong. What the survey and sweep readers
/// call for an object given as `mesh = "..."` (the file's vertex and triangle counts: call read_mesh and mesh_body).
[[nodiscard]] MeshBody read_mesh_body(const std::string& path, double unit_m, const BodyOptions& options);

/// Moves the positions of a body computed from a mesh read by read_mesh (centre of mass, support plane and polygon,
/// pivots; computed in the mesh's local frame) to the file's coordinates, adding mesh.origin_m: what `topple body`
/// prints, with the meaning these keys had before meshes were recentred. Lengths, angles and inertias do not change.
/// At rest (PoseMethod::rest) only x and y move: the rested body stands on z = 0, its heights measured from its base.
void to_file_coordinates(MeshBody& body, const Vec3& origin_m);

/// Same as read_mesh on a file's content already in memory, of `format` "obj", "off", "stl" or "ply" (what the
/// extension says); `name` is used in messages (and is what the fuzz targets call).
[[nodiscard]] TriangleMesh parse_mesh(std::string_view content, const std::string& format, const std::string& name,
                                      double unit_m = 1.0);

}  // namespace topple::io
