// Gmsh MSH 4.1 reader: a small file written here with triangles and quadrangles in
// three surfaces and physical groups (one surface in two groups), parametric node
// blocks, point and curve elements to ignore; the quads split along their shorter
// diagonal; selection by group name; broken files give ConfigError with file and line.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/config/config_error.hpp"
#include "sph_solver/walls/gmsh_reader.hpp"
#include "sph_solver/walls/mesh_topology.hpp"
#include "support/scratch_folder.hpp"
#include "support/text_files.hpp"

using namespace tankfsi::sph;
using Catch::Matchers::Contains;
using Eigen::Vector3d;
using tankfsi::ConfigError;
using tankfsi::testing::ScratchFolder;
using tankfsi::testing::with_line;
constexpr auto line_of = tankfsi::testing::line_number;
using tankfsi::testing::write_text;
namespace fs = std::filesystem;

namespace {

// Surface 1 ("floor"): two triangles on the unit square. Surface 2 ("tank wall"): the
// quad 2 5 6 3, whose diagonal 5–3 is shorter than 2–6. Surface 3 (groups "roof" and
// "tank wall", in that order): the quad 5 7 8 6, whose diagonal 5–8 is shorter than
// 7–6. Node 2 lies on a curve (parametric, one extra coordinate), nodes 7 and 8 in a
// parametric surface block (two). All elements counter-clockwise: normals +z.
const std::string good_msh = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
1 5 "rim"
2 1 "floor"
2 2 "tank wall"
2 3 "roof"
$EndPhysicalNames
$Entities
1 1 3 0
1 0 0 0 0
1 0 0 0 1 0 0 1 5 2 1 -2
1 0 0 0 1 1 0 1 1 4 1 2 3 4
2 1 0 0 2.6 1 0 1 2 0
3 2 0 0 4 1 0 2 3 2 0
$EndEntities
$Nodes
5 8 1 8
0 1 0 1
1
0 0 0
1 1 1 1
2
1 0 0 0.5
2 1 0 2
3
4
1 1 0
0 1 0
2 2 0 2
5
6
2 0 0
2.6 1 0
2 3 1 2
7
8
4 0 0 0.1 0.2
3 1 0 0.3 0.4
$EndNodes
$Elements
5 6 1 6
0 1 15 1
1 1
1 1 1 1
2 1 2
2 1 2 2
3 1 2 3
4 1 3 4
2 2 3 1
5 2 5 6 3
2 3 3 1
6 5 7 8 6
$EndElements
)";


// The triangle's corners as Gmsh node tags.
std::vector<std::int64_t> node_tags(const GmshSurface& surface, int t) {
  std::vector<std::int64_t> tags;
  for (const int v : surface.mesh.triangles()[static_cast<std::size_t>(t)])
    tags.push_back(surface.node_tag[static_cast<std::size_t>(v)]);
  return tags;
}

}  // namespace

TEST_CASE("Gmsh: triangles and quadrangles with physical groups", "[geometry]") {
  ScratchFolder folder;
  const GmshSurface surface = read_gmsh_surface(write_text(folder, "tank.msh", good_msh));
  REQUIRE(surface.mesh.triangle_count() == 6);
  CHECK(surface.mesh.vertex_count() == 8);
  CHECK(surface.node_tag == std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 8});
  CHECK(surface.mesh.vertices()[1] == Vector3d(1, 0, 0));  // parametric u skipped
  CHECK(surface.mesh.vertices()[7] == Vector3d(3, 1, 0));

  CHECK(node_tags(surface, 0) == std::vector<std::int64_t>{1, 2, 3});
  CHECK(node_tags(surface, 1) == std::vector<std::int64_t>{1, 3, 4});
  CHECK(node_tags(surface, 2) == std::vector<std::int64_t>{2, 5, 3});  // along 5–3
  CHECK(node_tags(surface, 3) == std::vector<std::int64_t>{5, 6, 3});
  CHECK(node_tags(surface, 4) == std::vector<std::int64_t>{5, 7, 8});  // along 5–8
  CHECK(node_tags(surface, 5) == std::vector<std::int64_t>{5, 8, 6});
  for (const auto& n : surface.mesh.face_normals()) CHECK(n == Vector3d::UnitZ());
  CHECK(check_topology(surface.mesh.vertices(), surface.mesh.triangles(), {false, 1e-12}).ok());

  CHECK(surface.physical_tag == std::vector<int>{1, 1, 2, 2, 3, 3});  // first group of surface 3
  CHECK(surface.physical_name(0) == "floor");
  CHECK(surface.physical_name(2) == "tank wall");
  CHECK(surface.physical_name(5) == "roof");
  CHECK(surface.physical_names.size() == 3);  // "rim" is a curve group
}

TEST_CASE("Gmsh: selection by physical group name", "[geometry]") {
  ScratchFolder folder;
  const fs::path file = write_text(folder, "tank.msh", good_msh);
  const GmshSurface wall = read_gmsh_surface(file, {"tank wall"});
  REQUIRE(wall.mesh.triangle_count() == 4);
  CHECK(wall.physical_tag == std::vector<int>{2, 2, 2, 2});  // surface 3 under its selected group
  CHECK(wall.node_tag == std::vector<std::int64_t>{2, 3, 5, 6, 7, 8});  // used nodes only, file order
  CHECK(node_tags(wall, 0) == std::vector<std::int64_t>{2, 5, 3});

  const GmshSurface two = read_gmsh_surface(file, {"roof", "floor"});
  CHECK(two.physical_tag == std::vector<int>{1, 1, 3, 3});

  CHECK_THROWS_WITH(read_gmsh_surface(file, {"lid"}),
                    Contains("no two-dimensional physical group named 'lid'") &&
                        Contains("'floor', 'tank wall', 'roof'"));
  CHECK_THROWS_WITH(read_gmsh_surface(file, {"rim"}), Contains("named 'rim'"));  // not a surface group
}

TEST_CASE("Gmsh: Windows line ends and skipped sections", "[geometry]") {
  ScratchFolder folder;
  std::string crlf;
  for (const char c : good_msh) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  crlf += "$Comments\r\nanything at all\r\n$EndComments\r\n";
  const GmshSurface surface = read_gmsh_surface(write_text(folder, "crlf.msh", crlf));
  CHECK(surface.mesh.triangle_count() == 6);
  CHECK(surface.physical_name(2) == "tank wall");
}

TEST_CASE("Gmsh: broken files raise ConfigError with file and line", "[geometry]") {
  ScratchFolder folder;
  const auto read = [&](const std::string& name, const std::string& text) {
    return read_gmsh_surface(write_text(folder, name, text));
  };

  SECTION("version 2.2 and binary files are refused with the way out") {
    CHECK_THROWS_AS(read("v2.msh", with_line(good_msh, 2, "2.2 0 8")), ConfigError);
    CHECK_THROWS_WITH(read("v2.msh", with_line(good_msh, 2, "2.2 0 8")),
                      Contains("v2.msh:2:") && Contains("unsupported MSH version 2.2") && Contains("4.1"));
    CHECK_THROWS_WITH(read("binary.msh", with_line(good_msh, 2, "4.1 1 8")),
                      Contains("binary.msh:2:") && Contains("binary MSH files are not supported"));
  }
  SECTION("unknown node tag: the element's line") {
    const int line = line_of(good_msh, "6 5 7 8 6");
    CHECK_THROWS_WITH(read("node.msh", with_line(good_msh, line, "6 5 7 99 6")),
                      Contains("node.msh:" + std::to_string(line) + ":") && Contains("unknown node tag 99"));
  }
  SECTION("malformed numbers") {
    const int line = line_of(good_msh, "2.6 1 0");
    CHECK_THROWS_WITH(read("coordinate.msh", with_line(good_msh, line, "2.6 1x 0")),
                      Contains("coordinate.msh:" + std::to_string(line) + ":") && Contains("found '1x'"));
    CHECK_THROWS_WITH(read("short.msh", with_line(good_msh, line, "2.6 1")),
                      Contains("short.msh:" + std::to_string(line) + ":") && Contains("node coordinates"));
    const int element = line_of(good_msh, "5 2 5 6 3");
    CHECK_THROWS_WITH(read("quad.msh", with_line(good_msh, element, "5 2 5 6")),
                      Contains("quad.msh:" + std::to_string(element) + ":") && Contains("4 node tags"));
  }
  SECTION("counts that disagree with their headers") {
    CHECK_THROWS_WITH(read("count.msh", with_line(good_msh, line_of(good_msh, "5 8 1 8"), "5 9 1 8")),
                      Contains("announces 9 nodes but its blocks hold 8"));
    const int header = line_of(good_msh, "5 6 1 6");
    CHECK_THROWS_WITH(read("blocks.msh", with_line(good_msh, header, "6 7 1 7")),
                      Contains("expected an element block") || Contains("unexpected end of file"));
  }
  SECTION("duplicate node tags") {
    CHECK_THROWS_WITH(read("twice.msh", with_line(good_msh, line_of(good_msh, "8"), "7")),
                      Contains("node tag 7 appears twice"));
  }
  SECTION("cut short: unexpected end of file in the section") {
    const std::string cut = good_msh.substr(0, good_msh.find("$EndElements"));
    CHECK_THROWS_WITH(read("cut.msh", cut), Contains("unexpected end of file inside $Elements"));
    const std::string no_end = good_msh.substr(0, good_msh.find("$EndNodes")) + "$Elements\n";
    CHECK_THROWS_WITH(read("end.msh", no_end), Contains("expected $EndNodes, found '$Elements'"));
  }
  SECTION("second-order surface elements are refused, not dropped") {
    const int block = line_of(good_msh, "2 1 2 2");
    CHECK_THROWS_WITH(read("order2.msh", with_line(good_msh, block, "2 1 9 2")),
                      Contains("order2.msh:" + std::to_string(block) + ":") && Contains("element type 9"));
  }
  SECTION("surface missing from $Entities") {
    const int line = line_of(good_msh, "2 3 3 1");
    CHECK_THROWS_WITH(read("entity.msh", with_line(good_msh, line, "2 4 3 1")),
                      Contains("entity.msh:" + std::to_string(line + 1) + ":") && Contains("surface entity 4"));
  }
  SECTION("not a Gmsh file, no triangles, missing file") {
    CHECK_THROWS_WITH(read("stl.msh", "solid x\nendsolid x\n"), Contains("stl.msh:1:") && Contains("$MeshFormat"));
    CHECK_THROWS_WITH(read("empty.msh", ""), Contains("empty file"));
    const std::string no_surfaces = good_msh.substr(0, good_msh.find("$Elements"));
    CHECK_THROWS_WITH(read("nothing.msh", no_surfaces), Contains("no triangles or quadrangles"));
    CHECK_THROWS_WITH(read_gmsh_surface(folder.file("missing.msh")), Contains("cannot read Gmsh file"));
  }
}
