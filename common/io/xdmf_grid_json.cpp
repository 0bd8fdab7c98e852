#include "common/io/xdmf_grid_json.hpp"

#include <nlohmann/json.hpp>

#include <stdexcept>

namespace tankfsi {

namespace {

using nlohmann::json;

json data_item_json(const XdmfDataItem& item) {
  return {{"dataset", item.dataset},
          {"dimensions", item.dimensions},
          {"number", item.number == XdmfNumber::float64 ? "float64" : "int64"}};
}

/// Whether j[key] is `second` rather than `first`; anything else is an error.
bool is_second_choice(const json& j, const std::string& key, const std::string& first, const std::string& second) {
  const auto value = j.at(key).get<std::string>();
  if (value != first && value != second)
    throw std::runtime_error(key + " '" + value + "' is neither '" + first + "' nor '" + second + "'");
  return value == second;
}

XdmfDataItem data_item_from(const json& j) {
  XdmfDataItem item;
  item.dataset = j.at("dataset").get<std::string>();
  item.dimensions = j.at("dimensions").get<std::vector<std::int64_t>>();
  item.number = is_second_choice(j, "number", "float64", "int64") ? XdmfNumber::int64 : XdmfNumber::float64;
  return item;
}

}  // namespace

std::string xdmf_grid_to_json(const XdmfGrid& grid) {
  json topology = {{"type", grid.topology.type == XdmfTopologyType::polyvertex ? "polyvertex" : "mixed"},
                   {"elements", grid.topology.elements}};
  if (grid.topology.connectivity) topology["connectivity"] = data_item_json(*grid.topology.connectivity);
  json attributes = json::array();
  for (const auto& attribute : grid.attributes)
    attributes.push_back({{"name", attribute.name},
                          {"center", attribute.center == XdmfCenter::node ? "node" : "cell"},
                          {"data", data_item_json(attribute.data)}});
  // nlohmann writes doubles in their shortest round-trip form: the time reads back exactly.
  const json j = {{"name", grid.name},
                  {"time", grid.time},
                  {"topology", topology},
                  {"geometry", data_item_json(grid.geometry)},
                  {"attributes", attributes}};
  return j.dump();
}

XdmfGrid xdmf_grid_from_json(const std::string& json_text) {
  try {
    const auto j = json::parse(json_text);
    XdmfGrid grid;
    grid.name = j.at("name").get<std::string>();
    grid.time = j.at("time").get<double>();
    const auto& topology = j.at("topology");
    grid.topology.type = is_second_choice(topology, "type", "polyvertex", "mixed") ? XdmfTopologyType::mixed
                                                                                    : XdmfTopologyType::polyvertex;
    grid.topology.elements = topology.at("elements").get<std::int64_t>();
    if (topology.contains("connectivity")) grid.topology.connectivity = data_item_from(topology.at("connectivity"));
    grid.geometry = data_item_from(j.at("geometry"));
    for (const auto& attribute : j.at("attributes")) {
      grid.attributes.push_back({attribute.at("name").get<std::string>(),
                                 is_second_choice(attribute, "center", "node", "cell") ? XdmfCenter::cell
                                                                                       : XdmfCenter::node,
                                 data_item_from(attribute.at("data"))});
    }
    return grid;
  } catch (const std::exception& error) {
    throw std::runtime_error(std::string("not an XDMF grid record: ") + error.what());
  }
}

}  // namespace tankfsi
