// libFuzzer target for the mesh reader (io::parse_mesh: topple's pre-checks and CGAL's OBJ, OFF, STL or PLY reader,
// the format fixed at compile time by TOPPLE_FUZZ_MESH) and what `topple body` computes on a mesh that reads. Contract (docs/fuzzing.md): an
// InputError, or a mesh that check_mesh accepts and whose planar body (at two azimuths) is all finite numbers with
// b1, b2, h > 0 (a refusal names the file); any other exception, a crash, a sanitizer report or a non-finite number ends the run.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <string_view>

#include "topple/bodies/body.hpp"
#include "topple/core/error.hpp"
#include "topple/io/mesh.hpp"

namespace {

void require_finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view content(reinterpret_cast<const char*>(data), size);
  try {
    const topple::TriangleMesh mesh = topple::io::parse_mesh(content, TOPPLE_FUZZ_MESH, "fuzz-mesh");
    require_finite({mesh.origin_m[0], mesh.origin_m[1], mesh.origin_m[2]});
    for (double azimuth : {0.0, 123.0}) {
      topple::BodyOptions options;
      options.azimuth_deg = azimuth;
      try {
        const topple::MeshBody b = topple::mesh_body(mesh, options, "fuzz-mesh");
        const auto& p = b.planar;
        require_finite({b.mass.volume_m3, b.mass.mass_kg, p.h_m, p.b1_m, p.b2_m, p.alpha1_rad, p.alpha2_rad,
                        p.inertia_o1_kg_m2, p.inertia_o2_kg_m2, p.p1_rad_s, p.p2_rad_s, p.p_sym_rad_s});
        if (!(p.b1_m > 0.0 && p.b2_m > 0.0 && p.h_m > 0.0 && b.mass.volume_m3 > 0.0)) std::abort();
      } catch (const topple::InputError&) {
        // a mesh that is a solid but does not stand (on a point, an edge, or leaning) is refused
      }
    }
  } catch (const topple::InputError& e) {
    // refusing bad input is the expected outcome; the refusal names the file (issue 31: file, line and field)
    if (e.where().file != "fuzz-mesh") std::abort();
  }
  return 0;
}
