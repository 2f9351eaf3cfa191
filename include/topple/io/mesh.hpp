#pragma once
// Reading a closed triangle mesh (a 3-D scan) for topple/bodies/body.hpp.
//
// Formats: Wavefront OBJ, STL (ASCII and binary), PLY (ASCII and binary), chosen by the file's extension (.obj,
// .stl, .ply, any case); any other extension is refused, so that the 40-odd other formats of the Open Asset Import
// Library (assimp, which parses these three) are never reached from topple. Polygons are split into triangles by
// topple (a fan; a polygon that is not convex is refused); the meshes of every object and group in the file are
// joined, with their node transforms applied; lines and points are refused. Vertices with bitwise-equal coordinates are welded into one (an STL file
// repeats each vertex in every triangle that uses it; OBJ and PLY index them): a scan whose neighbouring triangles
// do not share exactly equal vertices reads as open and is refused, nothing is snapped within a tolerance.
//
// Precision: Debian's assimp holds coordinates as float (ai_real; binary STL stores floats anyway), so a coordinate
// is read to 6e-8 relative (0.1 um on a 2 m rock, far below a scan's noise); everything after is double.
// A PLY header is first checked against the PLY grammar (assimp 5.2 loops forever on some malformed headers), and
// its element counts bounded by MeshLimits.
//
// Units: the file's numbers are multiplied by `unit_m` (1 for metres, 0.001 for millimetres) and read as x east,
// y north, z up. The mesh is then checked (check_mesh in topple/bodies/body.hpp); every refusal is an InputError naming the
// file.
#include <cstdint>
#include <string>
#include <string_view>

#include "topple/bodies/body.hpp"

namespace topple::io {

/// Largest mesh file read: 1 GiB (a binary STL of MeshLimits::max_triangles is 500 MB).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 30;

/// The length of one unit of the file's coordinates, m, from "m", "cm", "mm" (or any length unit that
/// parse_length_m knows, e.g. "in"). Throws InputError naming `field` otherwise.
[[nodiscard]] double mesh_unit_m(const std::string& unit, const std::string& field);

/// Reads `path` (OBJ, STL, PLY), scales it by `unit_m` and checks it (check_mesh). Throws InputError naming the file.
[[nodiscard]] TriangleMesh read_mesh(const std::string& path, double unit_m = 1.0);

/// A mesh file's planar body at options.azimuth_deg: check_body_options, then read_mesh (scaled by `unit_m`), then
/// mesh_body (its positions moved to the file's coordinates: to_file_coordinates). Throws InputError naming the mesh file, or the option that is wrong. What the survey and sweep readers
/// call for an object given as `mesh = "..."` (the file's vertex and triangle counts: call read_mesh and mesh_body).
[[nodiscard]] MeshBody read_mesh_body(const std::string& path, double unit_m, const BodyOptions& options);

/// Moves the positions of a body computed from a mesh read by read_mesh (centre of mass, support plane and polygon,
/// pivots; computed in the mesh's local frame) to the file's coordinates, adding mesh.origin_m: what `topple body`
/// prints, with the meaning these keys had before meshes were recentred. Lengths, angles and inertias do not change.
void to_file_coordinates(MeshBody& body, const Vec3& origin_m);

/// Same as read_mesh on a file's content already in memory, of `format` "obj", "stl" or "ply" (what the extension
/// says); `name` is used in messages (and is what the fuzz targets call).
[[nodiscard]] TriangleMesh parse_mesh(std::string_view content, const std::string& format, const std::string& name,
                                      double unit_m = 1.0);

}  // namespace topple::io
