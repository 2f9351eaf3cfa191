// Issue 31, the mesh cases: every bad mesh file is refused with the file, the line (text formats) and the field, in
// well under a second; counts a file cannot hold are refused before anything is read; numbers are whole tokens;
// coordinates quoted as typed; faces named by the file's own lines. Each row of the table was checked to fail on the
// main of before this change (the ones main already refused, with another message, are marked "main: ...").
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <future>
#include <string>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

#include "support/meshes.hpp"
#include "support/shared_data.hpp"
#include "topple/bodies/body.hpp"
#include "topple/core/error.hpp"
#include "topple/io/mesh.hpp"

namespace topple {
namespace {

using test::TempDir;
using test::write_file;

/// The box 0.5 x 0.25 x 2 as an OBJ of quads, its line 5 (vertex 5, "v 0 0 2") replaced by `line5`.
std::string box_obj(const std::string& line5 = "v 0 0 2") {
  return "v 0 0 0\nv 0.5 0 0\nv 0.5 0.25 0\nv 0 0.25 0\n" + line5 +
         "\nv 0.5 0 2\nv 0.5 0.25 2\nv 0 0.25 2\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
}

/// The unit tetrahedron as an ASCII PLY: `header` lines before end_header, vertex line 2 (of 4) as given.
std::string tet_ply(const std::string& header = "", const std::string& vertex2 = "1 0 0", const std::string& tail = "") {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 4\nproperty list uchar int vertex_indices\n" +
         header + "end_header\n0 0 0\n" + vertex2 + "\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n" + tail;
}

std::string facet(const std::vector<std::string>& corners) {
  std::string s = " facet normal 0 0 0\n  outer loop\n";
  for (const auto& c : corners) s += "   vertex " + c + "\n";
  return s + "  endloop\n endfacet\n";
}
/// The unit tetrahedron as an ASCII STL, its first facet's corners as given (line 2 is its facet line).
std::string tet_stl(const std::vector<std::string>& first = {"0 0 0", "0 1 0", "1 0 0"}) {
  return "solid t\n" + facet(first) + facet({"0 0 0", "1 0 0", "0 0 1"}) + facet({"0 0 0", "0 0 1", "0 1 0"}) +
         facet({"1 0 0", "0 1 0", "0 0 1"}) + "endsolid t\n";
}

/// A header declaring huge counts over a few bytes of data (the issue's 2 kB and 360-byte files).
std::string huge_ply(const std::string& format, int extra_properties, const std::string& counts_and_data) {
  std::string h = "ply\nformat " + format + " 1.0\nelement vertex 30000000\nproperty float x\nproperty float y\n"
                  "property float z\n";
  for (int i = 0; i < extra_properties; ++i) h += "property float p" + std::to_string(i) + "\n";
  return h + counts_and_data;
}

struct Case {
  const char* name;       // the file's name (its extension: the format)
  std::string content;
  std::string words;      // what the message must say (after "file:line: ")
  std::size_t line;       // the line the error names (0: none, a binary file)
};

std::vector<Case> cases() {
  std::string stl_binary = test::stl_binary_bytes(test::box_mesh(1, 1, 1));  // 12 facets, 684 bytes
  std::string stl_short = stl_binary.substr(0, 674);
  std::string stl_long = stl_binary + std::string(7, '\0');
  std::string stl_count = stl_binary;
  stl_count[80] = 11;  // 11 facets in a file of 12: main read 11 and called the box open
  std::string stl_solid = stl_binary.substr(0, 674);
  stl_solid.replace(0, 6, "solid ");  // a binary STL whose header begins "solid", cut short: main said "cannot be read"
  return {
      // Hangs and memory (main: 3 min 42 s and 481 MB in the issue's measurement; since issue 28 "cannot be read").
      {"counts_2kb.ply",
       huge_ply("ascii", 100, "element face 12\nproperty list uchar int vertex_indices\nend_header\n") +
           std::string(8 * 6, ' ').replace(0, 47, "0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n"),
       "element vertex 30000000: the count is too large for the file: 30000000 records of 103 values need at least "
       "6180000000 bytes",
       3},
      {"counts_360.ply",
       huge_ply("ascii", 0, "element face 10000000\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n"
                            "1 0 0\n0 1 0\n3 0 1 2\n"),
       "element vertex 30000000: the count is too large for the file", 3},
      {"counts_binary.ply",
       huge_ply("binary_little_endian", 0, "element face 10000000\nproperty list uchar int vertex_indices\n"
                                           "end_header\n") + std::string(100, '\0'),
       "need at least 360000000 bytes (binary, by the property types), but the file holds 100 bytes", 3},
      {"billion.ply",  // main: "an element line is not 'element NAME COUNT'"
       "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
       "element vertex 1000000000: the count is too large for the file", 3},
      {"faces_too_many.ply",  // the vertices fit; the faces' count does not
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 12345678\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "element face 12345678: the count is too large for the file", 7},
      {"digits.ply",
       "ply\nformat ascii 1.0\nelement vertex 123456789012345678901234567890\nproperty float x\nend_header\n",
       "the count is too large for any file", 3},
      // Silent guesses (main: "v 0 0 6D-1" read as z = 6 before issue 28; refused since, without the field).
      {"exponent.obj", box_obj("v 0 0 6D-1"), "vertex 5, z: '6D-1' is not a number", 5},
      {"suffix.obj", box_obj("v 0 0 0.3x"), "vertex 5, z: '0.3x' is not a number", 5},
      {"weight.obj", box_obj("v 0 0 2 2"), "vertex 5, w: a weight w = '2'", 5},  // main: accepted, w ignored
      {"face_token.obj", box_obj() + "f 1 2.5 3\n", "face 7, vertex 2: '2.5' is not a vertex number", 15},
      {"fourth_vertex.stl", tet_stl({"0 0 0", "0 1 0", "1 0 0", "5 5 5"}),  // main: "cannot be read as stl"
       "facet 1 (line 2), vertex 4: a fourth vertex: an STL facet is a triangle of three", 7},
      {"absent.ply",  // main: "cannot be read as ply"
       tet_ply("element extra0 2\nproperty float a\nelement extra1 2\nproperty float a\n"),
       "element extra0: the file ends in element 'extra0' (declared at line 9 with 2 records): 0 of them are there",
       22},
      {"half_absent.ply", tet_ply("element extra0 2\nproperty float a\n", "1 0 0", "7\n"),
       "the file ends in element 'extra0' (declared at line 9 with 2 records): 1 of them are there", 21},
      {"trailing.ply", tet_ply("", "1 0 0", "3 0 1 2\n"),
       "'3' after the last record the header declares (element 'face')", 18},
      // Messages: coordinates quoted as typed, with the vertex and the field.
      {"huge.obj", box_obj("v 0 0 1e300"), "vertex 5, z: '1e300' is beyond 1e+08 m of the file's origin", 5},
      {"beyond_double.obj", box_obj("v 1e400 0 2"), "vertex 5, x: '1e400' is beyond the range of a double", 5},
      {"inf.obj", box_obj("v 0 inf 2"), "vertex 5, y: 'inf' is not a finite number", 5},
      {"word.obj", box_obj("v 0 zero 2"), "vertex 5, y: 'zero' is not a number", 5},
      {"two.obj", box_obj("v 0 0"), "vertex 5: the v line holds 2 values where it needs x y z", 5},
      {"five.obj", box_obj("v 0 0 2 1 1"), "vertex 5: the v line holds 5 values", 5},
      {"minus.obj", box_obj("v 0 0 \xe2\x88\x92" "2"),
       "vertex 5, z: '\xe2\x88\x92" "2' is not a number: it holds the Unicode minus sign U+2212", 5},
      {"huge.ply", tet_ply("", "1 0 1e300"), "vertex 2 (index 1), z: '1e300' is beyond 1e+08 m", 11},
      {"index.ply", tet_ply("", "1 0 0", "").replace(tet_ply().find("3 0 1 3"), 7, "3 0 1.5 3"),
       "face 2, vertex_indices: '1.5' is not a whole number (int)", 15},
      {"huge.off", "OFF\n4 4 0\n0 0 0\n1 0 1e300\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
       "vertex 2 (index 1), z: '1e300' is beyond 1e+08 m", 4},
      {"huge.stl", tet_stl({"0 0 0", "0 1 0", "1e300 0 0"}), "facet 1, vertex 3, x: '1e300' is beyond 1e+08 m", 6},
      {"exponent.stl", tet_stl({"0 0 0", "0 1 0", "1 0 6D-1"}), "facet 1, vertex 3, z: '6D-1' is not a number", 6},
      // A quad is named by its f line (main: "triangle N" after splitting, before issue 28).
      {"quad_range.obj", box_obj().replace(box_obj().find("f 2 3 7 6"), 9, "f 2 3 9 6"),
       "face 4 at line 12 refers to vertex 9, but the file has 8 vertices", 0},
      {"no_x.ply",  // main of before issue 28: "degenerate"
       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float y\nproperty float z\nproperty float w\n"
       "element face 4\nproperty list uchar int vertex_indices\nend_header\n",
       "the vertex element has no property 'x'", 3},
      {"no_indices.ply",  // found by fuzz_mesh_ply: main said "cannot be read as ply" (CGAL printed its own line)
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int corners\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "the face element has no property 'vertex_indices'", 7},
      // Binary STL: the count against the size, both said (never CGAL's "$$$___magic___$$$").
      {"short.stl", stl_short, "as a binary STL of 12 facets (the count at bytes 80-83) it would be 84 + 50 x 12 = "
                               "684 bytes, but the file is 674 bytes (truncated", 0},
      {"long.stl", stl_long, "it would be 84 + 50 x 12 = 684 bytes, but the file is 691 bytes (data beyond the count",
       0},
      {"count.stl", stl_count, "as a binary STL of 11 facets (the count at bytes 80-83) it would be 84 + 50 x 11 = "
                               "634 bytes, but the file is 684 bytes", 0},
      {"solid_header.stl", stl_solid, "it would be 84 + 50 x 12 = 684 bytes, but the file is 674 bytes", 0},
  };
}

class MeshHardening : public ::testing::TestWithParam<std::size_t> {};

TEST_P(MeshHardening, RefusedWithFileLineAndField) {
  const Case c = cases()[GetParam()];
  SCOPED_TRACE(c.name);
  TempDir dir;
  const auto path = dir.path() / c.name;
  write_file(path, c.content);
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)io::read_mesh(path.string());
    FAIL() << c.name << " was accepted; expected: " << c.words;
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.where().file, path.string()) << m;
    EXPECT_NE(m.find(c.words), std::string::npos) << m;
    if (c.line != 0) {
      EXPECT_EQ(e.where().line.value_or(0), c.line) << m;
    }
  }
  // "Well under a second": these files are a few kB; the big counts are refused before anything is allocated.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
}

INSTANTIATE_TEST_SUITE_P(Issue31, MeshHardening, ::testing::Range(std::size_t{0}, cases().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& p) {
                           std::string n = cases()[p.param].name;
                           for (char& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
                           return n;
                         });

// What is read as before: w = 1 (OBJ's default weight) and x y z r g b (vertex colours) are the box.
TEST(MeshHardening, WeightOneAndVertexColoursAreRead) {
  TempDir dir;
  for (const std::string& line5 : {std::string("v 0 0 2 1"), std::string("v 0 0 2 0.5 0.5 0.5")}) {
    write_file(dir.path() / "box.obj", box_obj(line5));
    const TriangleMesh m = io::read_mesh((dir.path() / "box.obj").string());
    EXPECT_EQ(m.vertices_m.size(), 8u);
    EXPECT_NEAR(mass_properties(m, 1.0).volume_m3, 0.25, 1e-15) << line5;
  }
}

// mtllib names a FIFO that nobody writes: opening it would block forever. Geometry needs no material file, and none
// is opened (nor /dev/zero, nor a sparse 1 GB .mtl): the read returns at once.
TEST(MeshHardening, MaterialFilesAreNeverOpened) {
  TempDir dir;
  const auto fifo = dir.path() / "fifo.mtl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  const auto sparse = dir.path() / "sparse.mtl";
  {
    write_file(sparse, "");
    std::filesystem::resize_file(sparse, std::uintmax_t{1} << 30);
  }
  write_file(dir.path() / "box.obj",
             "mtllib fifo.mtl\nmtllib /dev/zero\nmtllib sparse.mtl\nusemtl stone\n" + box_obj());
  auto read = std::async(std::launch::async, [&] {
    return io::read_mesh((dir.path() / "box.obj").string()).vertices_m.size();
  });
  const bool prompt = read.wait_for(std::chrono::seconds(5)) == std::future_status::ready;
  if (!prompt) {
    // Unblock a reader stuck in open(2) on the FIFO (a writer end appears and closes), so the test ends.
    const int fd = ::open(fifo.c_str(), O_RDWR);
    if (fd >= 0) ::close(fd);
  }
  EXPECT_TRUE(prompt) << "an OBJ naming a FIFO in mtllib did not return within 5 s: the material file was opened";
  EXPECT_EQ(read.get(), 8u);
}

// Double precision: 8000.0 and 8000.0001 m are distinct points (in single precision both are 8000, and the tetrahedron
// would be a degenerate sliver); its volume is 1e-4 / 6 m^3 to the rounding of 8000.0001 (1e-12 m in 1e-4 m).
TEST(MeshHardening, PointsCloserThanAFloatResolvesAreDistinct) {
  TempDir dir;
  write_file(dir.path() / "thin.obj", "v 8000.0 0 0\nv 8000.0001 0 0\nv 8000.0 1 0\nv 8000 0 1\n"
                                      "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const TriangleMesh m = io::read_mesh((dir.path() / "thin.obj").string());
  EXPECT_EQ(m.vertices_m.size(), 4u);
  EXPECT_NE(static_cast<float>(8000.0001), static_cast<float>(8000.0 + 1e-3));  // guard: floats do resolve 1 mm
  EXPECT_EQ(static_cast<float>(8000.0001), static_cast<float>(8000.0));         // but not 0.1 mm
  EXPECT_NEAR(mass_properties(m, 1.0).volume_m3, 1e-4 / 6, 1e-8 * 1e-4 / 6);
}

// The single-precision offset case of issue 31: a 1.5 mm cube at x = 8000 m (float spacing there 0.49 mm: assimp's
// float reader gave b1 = 0.7324 mm). Read in double precision and recentred, b1 = 0.75 mm to 6e-8 relative (the
// docs' promise: 8000.0015 is 8000 + 0.0015 to 1e-12 m, 1e-9 of 1.5 mm).
TEST(MeshHardening, MillimetreBoxAt8000mKeepsItsHalfWidth) {
  TempDir dir;
  write_file(dir.path() / "mm.obj", "v 8000 0 0\nv 8000.0015 0 0\nv 8000.0015 0.0015 0\nv 8000 0.0015 0\n"
                                    "v 8000 0 0.0015\nv 8000.0015 0 0.0015\nv 8000.0015 0.0015 0.0015\n"
                                    "v 8000 0.0015 0.0015\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
                                    "f 4 1 5 8\n");
  BodyOptions o;
  o.azimuth_deg = 90.0;  // toward +x: b1, b2 are the half-width along x
  o.contact_tolerance_m = 1e-5;
  const MeshBody b = io::read_mesh_body((dir.path() / "mm.obj").string(), 1.0, o);
  EXPECT_NEAR(b.planar.b1_m, 0.75e-3, 6e-8 * 0.75e-3);
  EXPECT_NEAR(b.planar.b2_m, 0.75e-3, 6e-8 * 0.75e-3);
  EXPECT_NEAR(b.planar.h_m, 0.75e-3, 6e-8 * 0.75e-3);
}

}  // namespace
}  // namespace topple
