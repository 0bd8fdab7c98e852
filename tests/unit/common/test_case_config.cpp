// CaseConfig: values, defaults, overrides, paths and error locations, checked
// against the text of small case files written by the tests.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "common/config/case_config.hpp"
#include "common/config/case_schema.hpp"
#include "support/scratch_folder.hpp"

using namespace tankfsi;
namespace fs = std::filesystem;

namespace {

// A case file in a fresh folder of its own; removed with the object.
struct ScratchCase {
  testing::ScratchFolder scratch;
  fs::path folder = scratch.path();
  fs::path file;
  explicit ScratchCase(const std::string& text, const std::string& name = "case.yaml") : file(folder / name) {
    std::ofstream(file) << text;
  }
};

const char* base_fluid = R"(fluid:
  dimension: 2
  spacing: 0.01
  density: 1000
  viscosity: 0.001
)";

}  // namespace

TEST_CASE("values read back exactly and defaults fill the rest", "[config]") {
  ScratchCase c(std::string(base_fluid) + "structure:\n  analysis: modal\n  material: {young_modulus: 206e9, "
                                          "poisson_ratio: 0.3, density: 7900}\n");
  const auto config = CaseConfig::load(c.file, {}, case_schema());
  CHECK(config.integer("fluid.dimension") == 2);
  CHECK(config.real("fluid.spacing") == 0.01);
  CHECK(config.real("structure.material.young_modulus") == 206e9);
  CHECK(config.text("fluid.kernel") == "auto");                 // default
  CHECK(config.real("fluid.ppe.free_surface_threshold") == 0.97);  // default
  CHECK(config.text("fluid.time_step.mode") == "adaptive");
  CHECK(config.has("fluid.time_step.cfl"));      // applies to adaptive
  CHECK_FALSE(config.has("fluid.time_step.value"));  // only for fixed
  CHECK(config.integer("structure.modes") == 10);
  CHECK_FALSE(config.has("structure.time_step"));  // only for dynamic
  CHECK(config.has_section("fluid"));
  CHECK_FALSE(config.has_section("coupling"));  // model sections are not invented
  CHECK(config.has_section("output"));          // settings sections always exist
  CHECK(config.text("excitation.type") == "none");
  CHECK_FALSE(config.has("excitation.knet.x"));  // a key below an absent group
  CHECK_FALSE(config.has("coupling.implicit.max_iterations"));
  CHECK(config.records("fluid.probes").empty());
}

TEST_CASE("output.dir expands {case} and is made absolute; input paths are relative to the case", "[config]") {
  ScratchCase c(std::string(base_fluid) + "excitation:\n  type: csv\n  csv_file: motion.csv\n");
  std::ofstream(c.folder / "motion.csv") << "time_s,ax,ay,az\n0,0,0,0\n";
  const auto config = CaseConfig::load(c.file, {}, case_schema());
  CHECK(config.case_name() == c.folder.filename().string());  // case.yaml takes its folder's name
  CHECK(config.path("output.dir") == fs::absolute("runs/" + c.folder.filename().string()).lexically_normal());
  CHECK(config.path("excitation.csv_file") == (c.folder / "motion.csv").lexically_normal());
}

TEST_CASE("overrides take precedence, are validated, and name themselves in errors", "[config]") {
  ScratchCase c(base_fluid, "tank.yaml");
  const auto config = CaseConfig::load(c.file, {{"fluid.spacing", "0.02", ""}, {"fluid.kernel", "wendland_c2", ""}},
                                       case_schema());
  CHECK(config.case_name() == "tank");
  CHECK(config.real("fluid.spacing") == 0.02);
  CHECK(config.text("fluid.kernel") == "wendland_c2");
  CHECK_THROWS_WITH(CaseConfig::load(c.file, {{"fluid.spacing", "0", ""}}, case_schema()),
                    "--set fluid.spacing=0: fluid.spacing: must be > 0, got 0");
  // A later semantic error about an overridden key points at the override.
  CHECK(std::string(config.error_at("fluid.spacing", "too coarse").what()) ==
        "--set fluid.spacing=0.02: fluid.spacing: too coarse");
}

TEST_CASE("semantic errors raised after validation name the file and line of the key", "[config]") {
  ScratchCase c("title: x\n" + std::string(base_fluid) +
                "  probes:\n    - name: a\n      quantity: pressure\n      position: [0.1, 0.2, 0]\n");
  const auto config = CaseConfig::load(c.file, {}, case_schema());
  CHECK(std::string(config.error_at("fluid.density", "above the roof").what()) ==
        c.file.string() + ":5: fluid.density: above the roof");
  const auto probes = config.records("fluid.probes");
  REQUIRE(probes.size() == 1);
  CHECK(probes[0].text("name") == "a");
  CHECK(probes[0].vector3("position") == Eigen::Vector3d(0.1, 0.2, 0.0));
  CHECK(std::string(probes[0].error_at("position", "outside the tank").what()) ==
        c.file.string() + ":10: fluid.probes[0].position: outside the tank");
}

TEST_CASE("the resolved case is a fixed point of validation", "[config]") {
  ScratchCase c(std::string(base_fluid) + "end_time: 3\nexcitation: {type: harmonic, amplitude: 0.5, frequency: 0.55}\n");
  const auto config = CaseConfig::load(c.file, {{"fluid.gravity", "9.80665", ""}}, case_schema());
  ScratchCase again(config.resolved_yaml());
  const auto reread = CaseConfig::load(again.file, {}, case_schema());
  auto body = [](const std::string& yaml) { return yaml.substr(yaml.find('\n') + 1); };  // drop the header line
  CHECK(body(reread.resolved_yaml()) == body(config.resolved_yaml()));
  CHECK(reread.real("fluid.gravity") == 9.80665);
}

TEST_CASE("a custom schema: record lists with conditional fields", "[config]") {
  Schema schema;
  schema.keys.push_back(record_list_key("walls", "walls").with_fields({
      choice_key("type", {"box", "file"}, "kind").is_required(),
      real_vector_key("min", "corner").with_length(3).is_required().only_when("type", {"box"}),
      input_path_key("path", "mesh").is_required().only_when("type", {"file"}),
  }));
  ScratchCase ok("walls:\n  - {type: box, min: [0, 0, 0]}\n");
  const auto config = CaseConfig::load(ok.file, {}, schema);
  REQUIRE(config.records("walls").size() == 1);
  CHECK(config.records("walls")[0].vector3("min") == Eigen::Vector3d::Zero());
  ScratchCase bad("walls:\n  - {type: box, min: [0, 0, 0]}\n  - {type: file}\n");
  CHECK_THROWS_WITH(CaseConfig::load(bad.file, {}, schema),
                    bad.file.string() + ":3: walls[1].path: required key is missing (needed when walls[1].type is file)");
  ScratchCase wrong("walls:\n  - {type: box, min: [0, 0, 0], path: a.stl}\n");
  CHECK_THROWS_WITH(CaseConfig::load(wrong.file, {}, schema),
                    wrong.file.string() + ":2: walls[0].path: only used when walls[0].type is file (here it is box)");
}
