// Gmsh shell meshes: a plate of one quadrangle and two triangles written here
// as MSH 4.1, with surface, curve and point groups and a geometric point's
// node that no element uses; regions, element sets and node sets from the
// groups; every kind of broken file refused with its file and line.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>

#include "common/config/config_error.hpp"
#include "fem_solver/mesh/gmsh_shell_mesh.hpp"
#include "support/scratch_folder.hpp"
#include "support/text_files.hpp"

using namespace tankfsi::fem;
using Catch::Matchers::Contains;
using tankfsi::ConfigError;
using tankfsi::testing::ScratchFolder;
using tankfsi::testing::with_line;
constexpr auto line_of = tankfsi::testing::line_number;
using tankfsi::testing::write_text;

namespace {

// The plate [0, 2] x [0, 1] in z = 0, normals +z: surface 1 ("plate_a") is the
// quadrangle 1 2 5 6, surface 2 ("plate_b" and "loaded") the triangles 2 3 4
// and 2 4 5. Curve 1 ("left_edge") is the line 1–6, point 3 ("corner") node 3.
// Node 7 is point 7's (a circle centre, say): in no element.
const std::string plate_msh = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
5
0 4 "corner"
1 3 "left_edge"
2 1 "plate_a"
2 2 "plate_b"
2 5 "loaded"
$EndPhysicalNames
$Entities
3 1 2 0
1 0 0 0 0
3 2 0 0 1 4
7 5 5 5 0
1 0 0 0 0 1 0 1 3 2 1 -7
1 0 0 0 1 1 0 1 1 0
2 1 0 0 2 1 0 2 2 5 0
$EndEntities
$Nodes
6 7 1 7
0 1 0 1
1
0 0 0
0 3 0 1
3
2 0 0
0 7 0 1
7
5 5 5
1 1 0 1
6
0 1 0
2 1 0 2
2
5
1 0 0
1 1 0
2 2 0 1
4
2 1 0
$EndNodes
$Elements
4 5 1 5
0 3 15 1
1 3
1 1 1 1
2 1 6
2 1 3 1
3 1 2 5 6
2 2 2 2
4 2 3 4
5 2 4 5
$EndElements
)";

std::string at_line(const std::string& name, int line) { return name + ":" + std::to_string(line) + ": "; }

}  // namespace

TEST_CASE("Gmsh shell mesh: quadrangles and triangles, regions, element and node sets", "[fem][mesh][gmsh]") {
  ScratchFolder folder;
  const ShellMesh mesh = read_gmsh_shell_mesh(write_text(folder, "plate.msh", plate_msh), {"plate_a", "plate_b"});
  // Six nodes in file order (tags 1 3 6 2 5 4); node 7 of point 7 left out.
  REQUIRE(mesh.nodes.size() == 6);
  CHECK(mesh.nodes[0] == Eigen::Vector3d(0, 0, 0));
  CHECK(mesh.nodes[1] == Eigen::Vector3d(2, 0, 0));
  CHECK(mesh.nodes[2] == Eigen::Vector3d(0, 1, 0));
  CHECK(mesh.nodes[5] == Eigen::Vector3d(2, 1, 0));
  REQUIRE(mesh.elements.size() == 3);
  CHECK(mesh.quad_count() == 1);
  CHECK(mesh.triangle_count() == 2);
  CHECK(mesh.elements[0].nodes == std::array<int, 4>{0, 3, 4, 2});  // tags 1 2 5 6
  CHECK(mesh.elements[1].nodes == std::array<int, 4>{3, 1, 5, -1});  // tags 2 3 4
  CHECK(mesh.region_names == std::vector<std::string>{"plate_a", "plate_b"});
  CHECK(mesh.elements[0].region == 0);
  CHECK(mesh.elements[2].region == 1);
  CHECK(mesh.elements_of("plate_b") == std::vector<int>{1, 2});
  CHECK(mesh.element_sets.at("loaded") == std::vector<int>{1, 2});  // the group that is not a region
  CHECK(mesh.node_sets.at("left_edge") == std::vector<int>{0, 2});
  CHECK(mesh.node_sets.at("corner") == std::vector<int>{1});
  CHECK(mesh.nodes_of("loaded") == std::vector<int>{1, 3, 4, 5});
  CHECK(mesh.node_normals.empty());  // a file knows no exact normals
  CHECK_NOTHROW(mesh.check());
}

TEST_CASE("Gmsh shell mesh: default regions, files without groups", "[fem][mesh][gmsh]") {
  ScratchFolder folder;
  SECTION("every surface group is a region when each element is in one") {
    const std::string one_group = with_line(plate_msh, line_of(plate_msh, "2 1 0 0 2 1 0 2 2 5 0"), "2 1 0 0 2 1 0 1 2 0");
    const ShellMesh mesh = read_gmsh_shell_mesh(write_text(folder, "regions.msh", one_group));
    CHECK(mesh.region_names == std::vector<std::string>{"plate_a", "plate_b"});
    CHECK(mesh.element_sets.count("loaded") == 0);  // a group of no surface
  }
  SECTION("a surface in two default regions asks for structure.mesh.regions") {
    CHECK_THROWS_WITH(read_gmsh_shell_mesh(write_text(folder, "two.msh", plate_msh)),
                      Contains(at_line(folder.file("two.msh").string(), line_of(plate_msh, "2 2 2 2"))) &&
                          Contains("surface 2 is in two regions, 'plate_b' and 'loaded'") &&
                          Contains("structure.mesh.regions"));
  }
  SECTION("no groups at all: one region 'shell'") {
    std::string bare = with_line(plate_msh, line_of(plate_msh, "1 0 0 0 1 1 0 1 1 0"), "1 0 0 0 1 1 0 0 0");
    bare = with_line(bare, line_of(bare, "2 1 0 0 2 1 0 2 2 5 0"), "2 1 0 0 2 1 0 0 0");
    bare = with_line(bare, line_of(bare, "3 2 0 0 1 4"), "3 2 0 0 0");
    bare = with_line(bare, line_of(bare, "1 0 0 0 0 1 0 1 3 2 1 -7"), "1 0 0 0 0 1 0 0 2 1 -7");
    bare = bare.substr(0, bare.find("$PhysicalNames")) + bare.substr(bare.find("$Entities"));
    const ShellMesh mesh = read_gmsh_shell_mesh(write_text(folder, "bare.msh", bare));
    CHECK(mesh.region_names == std::vector<std::string>{"shell"});
    CHECK(mesh.elements.size() == 3);
    CHECK(mesh.node_sets.empty());
  }
}

TEST_CASE("Gmsh shell mesh: broken files name the file and line", "[fem][mesh][gmsh]") {
  ScratchFolder folder;
  const auto read = [&](const std::string& name, const std::string& text) {
    return read_gmsh_shell_mesh(write_text(folder, name, text), {"plate_a", "plate_b"});
  };
  const auto file = [&](const std::string& name, int line) { return at_line(folder.file(name).string(), line); };

  SECTION("a region the file does not have") {
    CHECK_THROWS_AS(read_gmsh_shell_mesh(write_text(folder, "plate.msh", plate_msh), {"plate_a", "roof"}),
                    std::out_of_range);
    CHECK_THROWS_WITH(read_gmsh_shell_mesh(write_text(folder, "plate.msh", plate_msh), {"plate_a", "roof"}),
                      Contains("plate.msh has no two-dimensional physical group named 'roof'") &&
                          Contains("'plate_a', 'plate_b', 'loaded'"));
  }
  SECTION("second-order and volume elements") {
    const int block = line_of(plate_msh, "2 2 2 2");
    CHECK_THROWS_WITH(read("order2.msh", with_line(plate_msh, block, "2 2 9 2")),
                      Contains(file("order2.msh", block)) && Contains("element type 9 (6-node triangle)") &&
                          Contains("not supported"));
    CHECK_THROWS_WITH(read("volume.msh", with_line(plate_msh, block, "3 1 4 2")),
                      Contains(file("volume.msh", block)) && Contains("volume elements (4-node tetrahedron)"));
  }
  SECTION("truncated") {
    const std::string cut = plate_msh.substr(0, plate_msh.find("5 2 4 5"));
    CHECK_THROWS_AS(read("cut.msh", cut), ConfigError);
    CHECK_THROWS_WITH(read("cut.msh", cut), Contains("cut.msh:") && Contains("unexpected end of file inside $Elements"));
  }
  SECTION("degenerate element") {
    // Node 3 moved onto the line 2–4: the triangle 2 3 4 has no area.
    const std::string flat = with_line(plate_msh, line_of(plate_msh, "2 0 0"), "1.5 0.5 0");
    CHECK_THROWS_WITH(read("flat.msh", flat), Contains(file("flat.msh", line_of(plate_msh, "4 2 3 4"))) &&
                                                  Contains("element 4 is degenerate"));
  }
  SECTION("inverted element: a self-crossing quadrangle") {
    const int quad = line_of(plate_msh, "3 1 2 5 6");
    CHECK_THROWS_WITH(read("bowtie.msh", with_line(plate_msh, quad, "3 1 2 6 5")),
                      Contains(file("bowtie.msh", quad)) && Contains("element 3 is inverted"));
  }
  SECTION("a triangle oriented against its neighbours") {
    const int triangle = line_of(plate_msh, "5 2 4 5");
    CHECK_THROWS_WITH(read("flipped.msh", with_line(plate_msh, triangle, "5 2 5 4")),
                      Contains(file("flipped.msh", line_of(plate_msh, "3 1 2 5 6"))) &&
                          Contains("elements 3 and 5 (line " + std::to_string(triangle) + ") are oriented oppositely"));
  }
  SECTION("a loose node and a group node outside the shell") {
    const int block = line_of(plate_msh, "0 7 0 1");
    CHECK_THROWS_WITH(read("loose.msh", with_line(plate_msh, block, "2 1 0 1")),
                      Contains(file("loose.msh", block + 1)) && Contains("node 7 belongs to no shell element"));
    const int point = line_of(plate_msh, "1 3");
    CHECK_THROWS_WITH(read("group.msh", with_line(plate_msh, point, "1 7")),
                      Contains(file("group.msh", block + 1)) &&
                          Contains("node 7 of physical group 'corner' belongs to no shell element"));
  }
  SECTION("an element naming a node the file does not have") {
    const int triangle = line_of(plate_msh, "5 2 4 5");
    CHECK_THROWS_WITH(read("unknown.msh", with_line(plate_msh, triangle, "5 2 4 9")),
                      Contains(file("unknown.msh", triangle)) && Contains("unknown node tag 9"));
  }
}
