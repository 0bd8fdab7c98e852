// STL reader: ASCII and binary files of the same mesh, written here byte by byte,
// read back to the same shared-vertex mesh; broken files give ConfigError with the
// line (ASCII) or byte offset and triangle (binary).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "common/config/config_error.hpp"
#include "sph_solver/walls/mesh_topology.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "sph_solver/walls/stl_reader.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"
#include "support/scratch_folder.hpp"
#include "support/text_files.hpp"

using namespace tankfsi::sph;
using Catch::Matchers::Contains;
using Eigen::Vector3d;
using tankfsi::ConfigError;
using tankfsi::testing::ScratchFolder;
using tankfsi::testing::with_line;
using tankfsi::testing::write_text;
namespace fs = std::filesystem;

namespace {

// Coordinates exactly representable in float32, so ASCII and binary agree bit for bit.
TriangleMesh test_cube() { return make_box(Vector3d(-0.5, -0.25, 0.0), Vector3d(1.5, 0.75, 2.0), NormalSide::inward); }

std::string ascii_stl(const TriangleMesh& mesh) {
  std::ostringstream out;
  out << std::setprecision(std::numeric_limits<float>::max_digits10);
  out << "solid test_cube\n";
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vector3d& n = mesh.face_normals()[t];
    out << "  facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n    outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Vector3d& x = mesh.corner(static_cast<int>(t), k);
      out << "      vertex " << x.x() << " " << x.y() << " " << x.z() << "\n";
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid test_cube\n";
  return out.str();
}

void put_u32(std::string& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xffu));
}
void put_float(std::string& out, double value) { put_u32(out, std::bit_cast<std::uint32_t>(static_cast<float>(value))); }

// Header deliberately starting with "solid", as some exporters write it.
std::string binary_stl(const TriangleMesh& mesh) {
  std::string out = "solid test_cube, binary";
  out.resize(80, ' ');
  put_u32(out, static_cast<std::uint32_t>(mesh.triangle_count()));
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) put_float(out, mesh.face_normals()[t][c]);
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) put_float(out, mesh.corner(static_cast<int>(t), k)[c]);
    out.append(2, '\0');
  }
  return out;
}


}  // namespace

TEST_CASE("STL: ASCII and binary files of a cube read back to the same merged mesh", "[wall_geometry]") {
  ScratchFolder folder;
  const TriangleMesh cube = test_cube();
  // Extension deliberately wrong for the binary one: detection is by content.
  const TriangleMesh from_ascii = read_stl(write_text(folder, "cube_ascii.stl", ascii_stl(cube)));
  const TriangleMesh from_binary = read_stl(write_text(folder, "cube_binary.txt", binary_stl(cube)));
  for (const TriangleMesh* mesh : {&from_ascii, &from_binary}) {
    REQUIRE(mesh->vertex_count() == 8);
    REQUIRE(mesh->triangle_count() == 12);
    CHECK(check_topology(mesh->vertices(), mesh->triangles()).ok());
    for (int t = 0; t < 12; ++t)
      for (int k = 0; k < 3; ++k) CHECK(mesh->corner(t, k) == cube.corner(t, k));
  }
  CHECK(from_ascii.vertices() == from_binary.vertices());
  CHECK(from_ascii.triangles() == from_binary.triangles());
  // Orientation comes from the vertex order (inward normals here), not from the file's normals.
  for (std::size_t t = 0; t < 12; ++t) CHECK(from_ascii.face_normals()[t] == cube.face_normals()[t]);
}

TEST_CASE("STL: ASCII details (case, several solids, -0, facet normals ignored)", "[wall_geometry]") {
  ScratchFolder folder;
  const std::string text =
      "SOLID a\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "endsolid a\nsolid b\nfacet normal 9 9 9\n outer loop\n vertex -0 0 0\n vertex 0 1e0 +0\n vertex 0 0 1\n"
      " endloop\n endfacet\nendsolid\n";
  const TriangleMesh mesh = read_stl(write_text(folder, "two.stl", text));
  CHECK(mesh.triangle_count() == 2);
  CHECK(mesh.vertex_count() == 4);  // (0,0,0) = (-0,0,0) and (0,1,0) shared
}

TEST_CASE("STL: broken files raise ConfigError with their location", "[wall_geometry]") {
  ScratchFolder folder;
  const TriangleMesh cube = test_cube();
  const std::string ascii = ascii_stl(cube);
  const std::string binary = binary_stl(cube);

  SECTION("truncated binary: byte offset and triangle") {
    const fs::path file = write_text(folder, "cut.stl", binary.substr(0, binary.size() - 30));
    CHECK_THROWS_AS(read_stl(file), ConfigError);
    CHECK_THROWS_WITH(read_stl(file), Contains(file.string()) && Contains("truncated binary STL") &&
                                          Contains("byte offset 654") && Contains("inside triangle 11"));
  }
  SECTION("binary with extra bytes") {
    const fs::path file = write_text(folder, "long.stl", binary + "xx");
    CHECK_THROWS_WITH(read_stl(file), Contains("2 unexpected bytes") && Contains("byte offset 684"));
  }
  SECTION("NaN coordinate in binary: triangle and byte offset") {
    std::string bad = binary;
    const std::size_t offset = 84 + 50 * 5 + 12 + 12 * 1 + 4 * 2;  // triangle 5, vertex 1, z
    const auto nan = std::bit_cast<std::uint32_t>(std::numeric_limits<float>::quiet_NaN());
    std::string bytes;
    put_u32(bytes, nan);
    bad.replace(offset, 4, bytes);
    CHECK_THROWS_WITH(read_stl(write_text(folder, "nan.stl", bad)),
                      Contains("triangle 5, vertex 1") && Contains("byte offset " + std::to_string(offset)));
  }
  SECTION("zero triangles") {
    std::string empty = binary.substr(0, 80);
    put_u32(empty, 0);
    CHECK_THROWS_WITH(read_stl(write_text(folder, "empty.stl", empty)), Contains("zero triangles"));
    CHECK_THROWS_WITH(read_stl(write_text(folder, "empty_ascii.stl", "solid x\nendsolid x\n")),
                      Contains("empty_ascii.stl:2") && Contains("zero triangles"));
  }
  SECTION("bad ASCII keyword: file and line") {
    const fs::path file = write_text(folder, "keyword.stl", with_line(ascii, 10, "    outer lop"));
    CHECK_THROWS_WITH(read_stl(file), Contains(file.string() + ":10:") && Contains("expected 'loop', found 'lop'"));
  }
  SECTION("NaN and non-numeric ASCII coordinates: file and line") {
    const fs::path nan = write_text(folder, "nan_ascii.stl", with_line(ascii, 4, "      vertex 0 nan 1"));
    CHECK_THROWS_WITH(read_stl(nan), Contains(nan.string() + ":4:") && Contains("expected a vertex coordinate, found the non-finite 'nan'"));
    const fs::path word = write_text(folder, "word.stl", with_line(ascii, 5, "      vertex 0 1 one"));
    CHECK_THROWS_WITH(read_stl(word), Contains(word.string() + ":5:") && Contains("found 'one'"));
  }
  SECTION("ASCII cut short: unexpected end of file at the last line") {
    const std::string cut = ascii.substr(0, ascii.find("    endloop"));  // ends after line 6
    CHECK_THROWS_WITH(read_stl(write_text(folder, "short.stl", cut)),
                      Contains("short.stl:6:") && Contains("unexpected end of file, expected 'endloop'"));
  }
  SECTION("neither ASCII nor binary, and missing files") {
    CHECK_THROWS_WITH(read_stl(write_text(folder, "tiny.stl", "hello")), Contains("not an STL file"));
    CHECK_THROWS_AS(read_stl(folder.file("missing.stl")), ConfigError);
    CHECK_THROWS_WITH(read_stl(folder.file("missing.stl")), Contains("cannot read STL file"));
  }
}
