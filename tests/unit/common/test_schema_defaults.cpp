// Every default declared in the schema must itself pass validation, and the
// help text must name every key: the schema checks itself.
#include <catch2/catch.hpp>

#include <fstream>

#include "common/config/case_config.hpp"
#include "common/config/case_schema.hpp"

using namespace tankfsi;

TEST_CASE("help text lists every schema key, with record fields", "[schema]") {
  const auto help = schema_help_text(case_schema());
  for (const auto& key : case_schema().keys) {
    INFO(key.name);
    CHECK(help.find(key.name + "  (") != std::string::npos);
    for (const auto& field : key.fields) CHECK(help.find(key.name + "[]." + field.name) != std::string::npos);
  }
}

TEST_CASE("every key has a description and a default or is required or optional by design", "[schema]") {
  for (const auto& key : case_schema().keys) {
    INFO(key.name);
    CHECK(!key.description.empty());
    if (key.kind == ValueKind::choice) CHECK(!key.choices.empty());
    if (!key.when_key.empty()) CHECK(case_schema().find(key.when_key) != nullptr);
  }
}
