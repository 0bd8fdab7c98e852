// The MSH 4.1 parser on its own: every dimension's physical names and entity
// groups, node blocks, element blocks with their lines, node counts checked
// for Gmsh's types and not for others, and a block refused by its header.
#include <catch2/catch.hpp>

#include <string>

#include "common/io/gmsh_msh.hpp"
#include "support/scratch_folder.hpp"
#include "support/text_files.hpp"

using Catch::Matchers::Contains;
using tankfsi::testing::ScratchFolder;
using tankfsi::testing::line_number;
using tankfsi::testing::with_line;
using tankfsi::testing::write_text;
namespace gmsh = tankfsi::gmsh;

namespace {

// A point (group "tip"), a curve (group "edge") and a surface (group "face")
// with one element each, and a block of an element type outside Gmsh's table.
const std::string small_msh = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
0 7 "tip"
1 8 "edge"
2 9 "face"
$EndPhysicalNames
$Entities
1 1 1 0
1 0 0 0 1 7
1 0 0 0 1 0 0 1 8 0
1 0 0 0 1 1 0 1 9 0
$EndEntities
$Nodes
1 3 1 3
2 1 0 3
1
2
3
0 0 0
1 0 0
0 1 0
$EndNodes
$Elements
4 4 1 4
0 1 15 1
1 1
1 1 1 1
2 1 2
2 1 2 1
3 1 2 3
2 1 99 1
4 1 2 3 1 2
$EndElements
)";

}  // namespace

TEST_CASE("MSH parser: names, entities, nodes and element blocks of every dimension", "[io][gmsh]") {
  ScratchFolder folder;
  const gmsh::MshFile msh = gmsh::read_msh(write_text(folder, "small.msh", small_msh));
  CHECK(msh.physical_tag(0, "tip") == 7);
  CHECK(msh.physical_tag(1, "edge") == 8);
  CHECK(msh.physical_tag(2, "face") == 9);
  CHECK(msh.physical_tag(2, "edge") == -1);  // names belong to one dimension
  CHECK(msh.listed_names(1) == "'edge'");
  CHECK(msh.listed_names(3) == "none");
  CHECK(msh.groups_of(0, 1, 0) == std::vector<int>{7});
  CHECK(msh.groups_of(1, 1, 0) == std::vector<int>{8});
  CHECK(msh.groups_of(2, 1, 0) == std::vector<int>{9});
  CHECK_THROWS_WITH(msh.groups_of(2, 5, 40), Contains("small.msh:40:") && Contains("surface entity 5"));
  REQUIRE(msh.nodes.size() == 3);
  CHECK(msh.nodes[1].position == Eigen::Vector3d(1, 0, 0));
  CHECK(msh.nodes[1].entity_dimension == 2);
  CHECK(msh.nodes[1].line == line_number(small_msh, "2"));
  CHECK(msh.node(3, 0) == 2);
  CHECK_THROWS_WITH(msh.node(4, 12), Contains("small.msh:12:") && Contains("unknown node tag 4"));
  REQUIRE(msh.blocks.size() == 4);
  CHECK(msh.blocks[2].type == gmsh::triangle_3_node);
  CHECK(msh.blocks[2].line == line_number(small_msh, "2 1 2 1"));
  CHECK(msh.blocks[2].elements[0].nodes == std::vector<std::int64_t>{1, 2, 3});
  CHECK(msh.blocks[2].elements[0].line == line_number(small_msh, "3 1 2 3"));
  CHECK(msh.blocks[3].elements[0].nodes.size() == 5);  // type 99: kept as listed
  CHECK(gmsh::element_node_count(9) == 6);
  CHECK(gmsh::element_type_name(16) == "8-node quadrangle");
  CHECK(gmsh::element_type_name(99) == "type 99");
}

TEST_CASE("MSH parser: node counts of known types, blocks refused by the reader", "[io][gmsh]") {
  ScratchFolder folder;
  const int triangle = line_number(small_msh, "3 1 2 3");
  CHECK_THROWS_WITH(gmsh::read_msh(write_text(folder, "short.msh", with_line(small_msh, triangle, "3 1 2"))),
                    Contains("short.msh:" + std::to_string(triangle) + ":") &&
                        Contains("expected an element tag and 3 node tags, found 3 numbers"));
  const int block = line_number(small_msh, "2 1 99 1");
  const auto refuse_unknown = [](const gmsh::MshFile& in, const gmsh::MshElementBlock& header) {
    if (gmsh::element_node_count(header.type) == 0) throw in.error_at(header.line, "type not wanted");
  };
  CHECK_THROWS_WITH(gmsh::read_msh(write_text(folder, "refused.msh", small_msh), refuse_unknown),
                    Contains("refused.msh:" + std::to_string(block) + ": type not wanted"));
}
