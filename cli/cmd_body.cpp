// topple body MESH --azimuth DEG: the planar rocking body of a closed triangle mesh (a 3-D scan) in a vertical plane,
// at rest on a stable face of its convex hull (or as scanned), and the list of those faces.
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "pose_options.hpp"
#include "progress.hpp"
#include "topple/bodies/body.hpp"
#include "topple/bodies/pose.hpp"
#include "topple/output/body_json.hpp"
#include "topple/io/mesh.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {
namespace {

struct BodyCommandOptions {
  std::string mesh;
  double azimuth_deg = 0.0;
  BodyOptions body;
  std::string unit = "m";
  bool json = false;
  bool quiet = false;
  PoseOptionsText pose;
  bool list_faces = false;
};

/// --list-faces: the hull's faces of the (pre-rotated) mesh, numbered as --face takes them.
void print_faces(const BodyCommandOptions& o, const TriangleMesh& mesh) {
  check_mesh(mesh, o.mesh);
  const Vec3 centre = mass_properties(mesh, 1.0).centre_of_mass_m;
  const double tol = effective_contact_tolerance_m(mesh, o.body.contact_tolerance_m);
  const std::vector<RestingFace> faces = resting_faces(mesh, centre, pre_rotation(o.body), tol);
  if (o.json) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    j["file"] = o.mesh;
    j["contact_tolerance_m"] = tol;
    j["faces"] = io::resting_faces_json(faces);
    fmt::print("{}\n", j.dump(2));
    return;
  }
  std::size_t stable = 0;
  for (const auto& f : faces) stable += f.stable ? 1 : 0;
  fmt::print("{}: {} faces of the convex hull ({} stable), contact tolerance {:.3g} m\n", o.mesh, faces.size(), stable,
             tol);
  fmt::print("(tilt: of the face's outward normal from the scan's down; min a/g: the least static overturning "
             "acceleration b/h, toward the azimuth)\n");
  fmt::print("{:>6} {:>10} {:>7} {:>12} {:>9} {:>10} {:>10} {:>12}\n", "face", "tilt_deg", "stable", "area_m2",
             "contacts", "h_m", "min_a_g", "azimuth_deg");
  for (const auto& f : faces) {
    // An unstable face has no overturning acceleration (it tips without one): "-".
    const std::string min_g = f.stable ? fmt::format("{:.4g}", f.overturning.min_g) : "-";
    const std::string azimuth = f.stable ? fmt::format("{:.2f}", f.overturning.min_azimuth_deg) : "-";
    fmt::print("{:>6} {:>10.4f} {:>7} {:>12.6g} {:>9} {:>10.6g} {:>10} {:>12}\n", f.number, f.tilt_deg,
               f.stable ? "yes" : "no", f.area_m2, f.contact_vertices, f.h_m, min_g, azimuth);
  }
}


void print_body(const BodyCommandOptions& o, const MeshBody& r, std::size_t vertices, std::size_t triangles) {
  const auto& m = r.mass;
  const auto& b = r.planar;
  const auto& c = m.centre_of_mass_m;
  const auto& I = m.inertia_cm_kg_m2;
  require_finite({{"volume", m.volume_m3}, {"mass", m.mass_kg}, {"h", b.h_m}, {"b1", b.b1_m}, {"b2", b.b2_m},
                  {"I_O1", b.inertia_o1_kg_m2}, {"I_O2", b.inertia_o2_kg_m2}, {"p1", b.p1_rad_s},
                  {"p2", b.p2_rad_s}, {"p (symmetric)", b.p_sym_rad_s}});
  if (o.json) {
    fmt::print("{}\n", io::mesh_body_json(io::MeshBodyOutcome{r, o.mesh, io::mesh_unit_m(o.unit, "--unit"), vertices,
                                                             triangles, o.body.g_m_s2})
                            .dump(2));
    return;
  }
  fmt::print("file          {} ({} vertices, {} triangles; unit {})\n", o.mesh, vertices, triangles, o.unit);
  fmt::print("volume        {:.9g} m^3\n", m.volume_m3);
  fmt::print("mass          {:.9g} kg (density {:g} kg/m^3)\n", m.mass_kg, m.density_kg_m3);
  fmt::print("CM            ({:.9g}, {:.9g}, {:.9g}) m (x east, y north, z up)\n", c[0], c[1], c[2]);
  fmt::print("I about CM    [{:.6g} {:.6g} {:.6g}; {:.6g} {:.6g} {:.6g}; {:.6g} {:.6g} {:.6g}] kg m^2\n", I[0][0],
             I[0][1], I[0][2], I[1][0], I[1][1], I[1][2], I[2][0], I[2][1], I[2][2]);
  const Pose& pose = r.pose;
  if (pose.method == PoseMethod::as_scanned) {
    fmt::print("pose          as scanned (the lowest plane of the mesh as given)\n");
  } else {
    const auto& q = pose.rotation_wxyz;
    fmt::print("pose          rest on face {} of {} ({} stable; {}), tilted {:.4f} deg from the scan; rotation "
               "w,x,y,z = {:.9g},{:.9g},{:.9g},{:.9g} about the CM\n",
               *pose.face, pose.faces, pose.stable_faces, pose.chosen_by, pose.tilt_deg, q[0], q[1], q[2], q[3]);
  }
  fmt::print("support       z = {:.9g} m, {} vertices within {:.3g} m, hull of {} points\n", r.support.z_m,
             r.support.contact_vertices, r.support.tolerance_m, r.support.hull_xy_m.size());
  const auto& so = pose.overturning;
  fmt::print("static a/g    b/h = {:.6g} at least (toward azimuth {:.2f} deg); toward N {:.6g}, E {:.6g}, S {:.6g}, "
             "W {:.6g}\n",
             so.min_g, so.min_azimuth_deg, so.principal_g[0], so.principal_g[1], so.principal_g[2],
             so.principal_g[3]);
  fmt::print("plane         azimuth {:g} deg (clockwise from north; pivot 1 at the rear, pivot 2 toward the "
             "azimuth)\n",
             b.azimuth_deg);
  fmt::print("h             {:.9g} m\n", b.h_m);
  fmt::print("b1, b2        {:.9g} m, {:.9g} m\n", b.b1_m, b.b2_m);
  fmt::print("R1, R2        {:.9g} m, {:.9g} m\n", b.r1_m, b.r2_m);
  fmt::print("alpha1, 2     {:.6f} deg, {:.6f} deg ({:.9g}, {:.9g} rad)\n", rad_to_deg(b.alpha1_rad), rad_to_deg(b.alpha2_rad),
             b.alpha1_rad, b.alpha2_rad);
  fmt::print("I_cm (plane)  {:.9g} kg m^2\n", b.inertia_cm_kg_m2);
  fmt::print("I_O1, I_O2    {:.9g} kg m^2, {:.9g} kg m^2\n", b.inertia_o1_kg_m2, b.inertia_o2_kg_m2);
  fmt::print("p1, p2        {:.9g} rad/s, {:.9g} rad/s (g = {} m/s2)\n", b.p1_rad_s, b.p2_rad_s, o.body.g_m_s2);
  // The asymmetric planar body as `rock` takes it (rocking.hpp: b1 to the -x pivot, b2 to the +x pivot, x here
  // toward the azimuth; inertia = I_cm / m about the rocking axis).
  fmt::print("as rock       `topple rock --shape general --b1 {:.9g}m --b2 {:.9g}m --h {:.9g}m --inertia {:.9g}m2` "
             "(+x toward the azimuth)\n",
             b.b1_m, b.b2_m, b.h_m, b.inertia_cm_kg_m2 / m.mass_kg);
  fmt::print("symmetric     b = (b1 + b2)/2 = {:.9g} m, alpha = {:.6f} deg, p = {:.9g} rad/s (for information)\n",
             b.b_sym_m, rad_to_deg(b.alpha_sym_rad), b.p_sym_rad_s);
  fmt::print("              as `topple rock --shape general --a {:.9g}m --h {:.9g}m --D {:.9g}m2`\n", b.b_sym_m,
             b.h_m, b.d_sym_m2);
}

}  // namespace

void add_body_command(CLI::App& app) {
  auto o = std::make_shared<BodyCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "body", "The planar rocking body of a closed triangle mesh (OBJ, OFF, STL, PLY; x east, y north, z up) in the "
              "vertical plane at an azimuth: volume, mass, centre of mass, inertia, pivots b1/b2, h, alpha1/2, "
              "I_O1/2, p1/p2");
  cmd->add_option("mesh", o->mesh,
                  "Mesh file: .obj, .off, .stl or .ply (ASCII or binary), a closed outward-facing solid; read in double "
                  "precision (georeferenced coordinates are fine)")
      ->required();
  cmd->add_option("--azimuth", o->azimuth_deg, "Direction of the plane of shaking, degrees clockwise from north (+y)")
      ->required();
  cmd->add_option("--density", o->body.density_kg_m3, "Uniform density, kg/m^3 (granite)")->capture_default_str();
  cmd->add_option("--unit", o->unit, "Unit of the mesh's coordinates: a unit (m, cm, mm, in, ft), a length per file "
                                     "unit (2cm) or a bare number of metres per file unit (0.001)")->capture_default_str();
  add_pose_options(*cmd, o->pose, o->body);
  cmd->add_flag("--list-faces", o->list_faces,
                "List the convex hull's faces (number, tilt from the scan, stable, area, least static overturning "
                "acceleration and its azimuth) and stop");
  cmd->add_option("--g", o->body.g_m_s2, "Gravitational acceleration, m/s2")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print one JSON object instead of text");
  add_quiet_flag(*cmd, o->quiet);  // quick: no bar; accepted so that every command takes --quiet
  cmd->callback([o, cmd] {
    check_g(o->body.g_m_s2);
    o->body.azimuth_deg = o->azimuth_deg;
    apply_pose_options(*cmd, o->pose, o->body);
    check_body_options(o->body);
    const double unit_m = io::mesh_unit_m(o->unit, "--unit");
    const TriangleMesh mesh = io::read_mesh(o->mesh, unit_m);
    if (o->list_faces) {
      if (o->body.pose == PoseMethod::as_scanned) {
        throw parameter_error("--list-faces", "lists the faces of the resting pose: not with --pose as-scanned");
      }
      print_faces(*o, mesh);
      return;
    }
    // Positions printed in the file's coordinates: the reader recentred the mesh (a translation) and the resting pose
    // turns it about its centre of mass, so adding the origin back is the same rotation about the CM done in the
    // file's frame (as scanned: exactly the file's positions, as before).
    MeshBody result = mesh_body(mesh, o->body, o->mesh);
    io::to_file_coordinates(result, mesh.origin_m);
    print_body(*o, result, mesh.vertices_m.size(), mesh.triangles.size());
  });
}

}  // namespace topple::cli
