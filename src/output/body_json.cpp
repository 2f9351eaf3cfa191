// The field table of a body from a mesh (io/body_json.hpp).
#include "topple/output/body_json.hpp"

#include "topple/core/units.hpp"

namespace topple::io {
namespace {

using O = MeshBodyOutcome;
using J = nlohmann::ordered_json;


J vec(const Vec3& v) { return J::array({v[0], v[1], v[2]}); }

const PlanarBody& planar(const O& o) { return o.body.planar; }

}  // namespace

const char* pose_method_name(PoseMethod method) {
  return method == PoseMethod::as_scanned ? "as-scanned" : "rest";
}

nlohmann::ordered_json static_overturning_json(const StaticOverturning& s) {
  J j;
  j["min_g"] = s.min_g;
  j["min_azimuth_deg"] = s.min_azimuth_deg;
  j["toward_north_g"] = s.principal_g[0];
  j["toward_east_g"] = s.principal_g[1];
  j["toward_south_g"] = s.principal_g[2];
  j["toward_west_g"] = s.principal_g[3];
  return j;
}

nlohmann::ordered_json resting_faces_json(const std::vector<RestingFace>& faces) {
  J out = J::array();
  for (const auto& f : faces) {
    J j;
    j["face"] = f.number;
    j["tilt_deg"] = f.tilt_deg;
    j["stable"] = f.stable;
    j["area_m2"] = f.area_m2;
    j["margin_m"] = f.margin_m;
    j["h_m"] = f.h_m;
    j["contact_vertices"] = f.contact_vertices;
    j["normal"] = vec(f.normal);
    J poly = J::array();
    for (const auto& p : f.polygon_xy_m) poly.push_back({p[0], p[1]});
    j["support_polygon_xy_m"] = poly;
    j["static_overturning"] = f.stable ? static_overturning_json(f.overturning) : J(nullptr);
    out.push_back(j);
  }
  return out;
}

const std::array<BodyField, 35> kMeshBodyFields{{
    {"file", [](const O& o) -> J { return o.file; }},
    {"unit_m", [](const O& o) -> J { return o.unit_m; }},
    {"vertices", [](const O& o) -> J { return o.vertices; }},
    {"triangles", [](const O& o) -> J { return o.triangles; }},
    {"density_kg_m3", [](const O& o) -> J { return o.body.mass.density_kg_m3; }},
    {"volume_m3", [](const O& o) -> J { return o.body.mass.volume_m3; }},
    {"mass_kg", [](const O& o) -> J { return o.body.mass.mass_kg; }},
    {"centre_of_mass_m", [](const O& o) -> J { return vec(o.body.mass.centre_of_mass_m); }},
    {"inertia_cm_kg_m2",
     [](const O& o) -> J {
       const auto& I = o.body.mass.inertia_cm_kg_m2;
       return J::array({vec(I[0]), vec(I[1]), vec(I[2])});
     }},
    {"support_z_m", [](const O& o) -> J { return o.body.support.z_m; }},
    {"support_tolerance_m", [](const O& o) -> J { return o.body.support.tolerance_m; }},
    {"support_contact_vertices", [](const O& o) -> J { return o.body.support.contact_vertices; }},
    {"support_polygon_xy_m",
     [](const O& o) -> J {
       J hull = J::array();
       for (const auto& p : o.body.support.hull_xy_m) hull.push_back({p[0], p[1]});
       return hull;
     }},
    {"azimuth_deg", [](const O& o) -> J { return planar(o).azimuth_deg; }},
    {"g_m_s2", [](const O& o) -> J { return o.g_m_s2; }},
    {"h_m", [](const O& o) -> J { return planar(o).h_m; }},
    {"b1_m", [](const O& o) -> J { return planar(o).b1_m; }},
    {"b2_m", [](const O& o) -> J { return planar(o).b2_m; }},
    {"r1_m", [](const O& o) -> J { return planar(o).r1_m; }},
    {"r2_m", [](const O& o) -> J { return planar(o).r2_m; }},
    {"alpha1_rad", [](const O& o) -> J { return planar(o).alpha1_rad; }},
    {"alpha2_rad", [](const O& o) -> J { return planar(o).alpha2_rad; }},
    {"alpha1_deg", [](const O& o) -> J { return rad_to_deg(planar(o).alpha1_rad); }},
    {"alpha2_deg", [](const O& o) -> J { return rad_to_deg(planar(o).alpha2_rad); }},
    {"inertia_cm_plane_kg_m2", [](const O& o) -> J { return planar(o).inertia_cm_kg_m2; }},
    {"inertia_o1_kg_m2", [](const O& o) -> J { return planar(o).inertia_o1_kg_m2; }},
    {"inertia_o2_kg_m2", [](const O& o) -> J { return planar(o).inertia_o2_kg_m2; }},
    {"d1_m2", [](const O& o) -> J { return planar(o).d1_m2; }},
    {"d2_m2", [](const O& o) -> J { return planar(o).d2_m2; }},
    {"p1_rad_s", [](const O& o) -> J { return planar(o).p1_rad_s; }},
    {"p2_rad_s", [](const O& o) -> J { return planar(o).p2_rad_s; }},
    {"pivot1_m", [](const O& o) -> J { return vec(planar(o).pivot1_m); }},
    {"pivot2_m", [](const O& o) -> J { return vec(planar(o).pivot2_m); }},
    // The symmetric equivalent b = (b1 + b2) / 2 (body.hpp), for information.
    {"symmetric",
     [](const O& o) -> J {
       const PlanarBody& b = planar(o);
       J s;
       s["b_m"] = b.b_sym_m;
       s["r_m"] = b.r_sym_m;
       s["alpha_rad"] = b.alpha_sym_rad;
       s["alpha_deg"] = rad_to_deg(b.alpha_sym_rad);
       s["d_m2"] = b.d_sym_m2;
       s["p_rad_s"] = b.p_sym_rad_s;
       return s;
     }},
    // Which pose produced the body (bodies/pose.hpp); "as-scanned" is the earlier answer.
    {"pose",
     [](const O& o) -> J {
       const Pose& p = o.body.pose;
       J j;
       j["method"] = pose_method_name(p.method);
       j["chosen_by"] = p.chosen_by;
       j["face"] = p.face ? J(*p.face) : J(nullptr);
       j["tilt_deg"] = p.tilt_deg;
       j["rotation_wxyz"] = J::array({p.rotation_wxyz[0], p.rotation_wxyz[1], p.rotation_wxyz[2], p.rotation_wxyz[3]});
       j["contact_tolerance_m"] = p.contact_tolerance_m;
       j["faces"] = p.faces;
       j["stable_faces"] = p.stable_faces;
       j["static_overturning"] = static_overturning_json(p.overturning);
       return j;
     }},
}};

nlohmann::ordered_json mesh_body_json(const MeshBodyOutcome& outcome) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const BodyField& field : kMeshBodyFields) j[field.name] = field.get(outcome);
  return j;
}

}  // namespace topple::io
