#!/usr/bin/python3
"""Independent check of a tankfsi field series: NAME.xdmf and the NAME.h5 it names.

Usage: check_field_series.py SERIES.xdmf [EXPECTED.json]

Reads the XDMF the way a viewer does (xml.etree, h5py, numpy; nothing from
tankfsi) and checks:
  - the document is a temporal collection of uniform grids with increasing times;
  - every DataItem names an existing dataset of the .h5 file (relative to the
    XDMF's folder) with the stated Dimensions, NumberType and Precision;
  - topologies are consistent: Polyvertex counts equal the geometry rows; Mixed
    connectivity holds exactly NumberOfElements cells of type 4 (triangle) or
    5 (quadrilateral) whose vertex indices are geometry rows;
  - attributes: Scalar is 1-D, Vector has 3 columns, Node/Cell rows match the
    vertices/cells; the time attribute of the geometry's step group equals the
    grid's Time;
  - with EXPECTED.json, every grid equals the expected step, bit for bit:
      {"steps": [{"time": t, "topology": "Polyvertex" | "Mixed", "elements": n,
                  "geometry": DATA, "connectivity": DATA (Mixed only),
                  "attributes": {NAME: {"center": "Node" | "Cell", **DATA}}}]}
    where DATA is {"shape": [rows] or [rows, columns], "values": [flat list]}.
Prints every mismatch found and exits 1 if there is any, else prints a summary
and exits 0 (2 for bad usage).
"""
import json
import os
import sys
import xml.etree.ElementTree as ElementTree

import h5py
import numpy as np

NUMPY_TYPES = {("Float", "8"): np.dtype("<f8"), ("Float", "4"): np.dtype("<f4"),
               ("Int", "8"): np.dtype("<i8"), ("Int", "4"): np.dtype("<i4")}
VERTICES_PER_CELL = {4: 3, 5: 4}  # XDMF type codes: triangle, quadrilateral


class SeriesChecker:
    def __init__(self, xdmf_path):
        self.xdmf_path = xdmf_path
        self.folder = os.path.dirname(os.path.abspath(xdmf_path))
        self.errors = []
        self.h5_files = {}

    def error(self, where, message):
        self.errors.append(f"{where}: {message}")

    def h5(self, name):
        if name not in self.h5_files:
            self.h5_files[name] = h5py.File(os.path.join(self.folder, name), "r")
        return self.h5_files[name]

    def read_data_item(self, where, item):
        """The array a DataItem names, after checking it matches its declaration; None if it does not."""
        if item is None:
            self.error(where, "no DataItem")
            return None
        if item.get("Format") != "HDF":
            self.error(where, f"Format {item.get('Format')!r}, expected 'HDF'")
            return None
        reference = (item.text or "").strip()
        file_name, _, dataset_path = reference.partition(":")
        if not dataset_path:
            self.error(where, f"DataItem text {reference!r} is not FILE:/dataset")
            return None
        where = f"{where} [{reference}]"
        try:
            h5_file = self.h5(file_name)
        except OSError as error:
            self.error(where, f"cannot open {file_name}: {error}")
            return None
        if dataset_path not in h5_file or not isinstance(h5_file[dataset_path], h5py.Dataset):
            self.error(where, "no such dataset")
            return None
        dataset = h5_file[dataset_path]
        dimensions = tuple(int(d) for d in item.get("Dimensions", "").split())
        if dataset.shape != dimensions:
            self.error(where, f"dataset shape {dataset.shape}, XDMF Dimensions {dimensions}")
            return None
        declared = (item.get("NumberType", "Float"), item.get("Precision", "4"))
        if NUMPY_TYPES.get(declared) != dataset.dtype:
            self.error(where, f"dataset type {dataset.dtype.str}, XDMF NumberType/Precision {declared}")
            return None
        return dataset[()]

    def check_mixed_connectivity(self, where, connectivity, elements, vertices):
        cells, position = 0, 0
        while position < len(connectivity):
            code = int(connectivity[position])
            if code not in VERTICES_PER_CELL:
                self.error(where, f"cell type code {code} at position {position}; only 4 and 5 are written")
                return
            indices = connectivity[position + 1: position + 1 + VERTICES_PER_CELL[code]]
            if len(indices) != VERTICES_PER_CELL[code]:
                self.error(where, "connectivity ends inside a cell")
                return
            if indices.min() < 0 or indices.max() >= vertices:
                self.error(where, f"cell {cells} names vertices {indices.tolist()}, outside 0..{vertices - 1}")
            position += 1 + VERTICES_PER_CELL[code]
            cells += 1
        if cells != elements:
            self.error(where, f"connectivity holds {cells} cells, NumberOfElements says {elements}")

    def check_grid(self, grid):
        """Structure of one uniform grid; returns what it holds, for the comparison with the expected data."""
        where = f"grid {grid.get('Name')!r}"
        found = {"attributes": {}}
        if grid.get("GridType", "Uniform") != "Uniform":
            self.error(where, f"GridType {grid.get('GridType')!r}, expected Uniform")
        time = grid.find("Time")
        found["time"] = float(time.get("Value")) if time is not None else None
        if found["time"] is None:
            self.error(where, "no <Time Value=...>")

        geometry = grid.find("Geometry")
        if geometry is None or geometry.get("GeometryType") != "XYZ":
            self.error(where, "no Geometry of GeometryType XYZ")
            return found
        found["geometry"] = positions = self.read_data_item(f"{where} Geometry", geometry.find("DataItem"))
        if positions is None:
            return found
        if positions.ndim != 2 or positions.shape[1] != 3:
            self.error(f"{where} Geometry", f"shape {positions.shape}, expected (n, 3)")
        vertices = positions.shape[0]
        self.check_step_time(where, geometry.find("DataItem"), found["time"])

        topology = grid.find("Topology")
        kind = topology.get("TopologyType") if topology is not None else None
        found["topology"] = kind
        elements = int(topology.get("NumberOfElements", "-1")) if topology is not None else -1
        found["elements"] = elements
        if kind == "Polyvertex":
            if elements != vertices:
                self.error(f"{where} Topology", f"Polyvertex of {elements} elements on {vertices} points")
        elif kind == "Mixed":
            connectivity = self.read_data_item(f"{where} Topology", topology.find("DataItem"))
            found["connectivity"] = connectivity
            if connectivity is not None:
                self.check_mixed_connectivity(f"{where} Topology", connectivity, elements, vertices)
        else:
            self.error(where, f"TopologyType {kind!r}; Polyvertex or Mixed are written")

        for attribute in grid.findall("Attribute"):
            name, center = attribute.get("Name"), attribute.get("Center")
            attribute_where = f"{where} Attribute {name!r}"
            if name in found["attributes"]:
                self.error(attribute_where, "appears twice")
            values = self.read_data_item(attribute_where, attribute.find("DataItem"))
            if values is None:
                continue
            found["attributes"][name] = {"center": center, "values": values}
            rows = {"Node": vertices, "Cell": elements}.get(center)
            if rows is None:
                self.error(attribute_where, f"Center {center!r}; Node or Cell are written")
            elif values.shape[0] != rows:
                self.error(attribute_where, f"{values.shape[0]} rows, the grid has {rows} {center.lower()}s")
            attribute_type = attribute.get("AttributeType")
            if attribute_type == "Scalar" and values.ndim != 1:
                self.error(attribute_where, f"Scalar of shape {values.shape}")
            elif attribute_type == "Vector" and (values.ndim != 2 or values.shape[1] != 3):
                self.error(attribute_where, f"Vector of shape {values.shape}")
            elif attribute_type not in ("Scalar", "Vector"):
                self.error(attribute_where, f"AttributeType {attribute_type!r}")
        return found

    def check_step_time(self, where, geometry_item, time):
        """tankfsi stores each snapshot's time as the attribute 'time' of its step group as well."""
        file_name, _, dataset_path = geometry_item.text.strip().partition(":")
        group = self.h5(file_name)[dataset_path].parent
        if "time" not in group.attrs:
            self.error(where, f"step group {group.name} has no time attribute")
        elif time is not None and not same_bits(np.float64(group.attrs["time"]), np.float64(time)):
            self.error(where, f"step group time {group.attrs['time']!r}, XDMF Time {time!r}")

    def check_document(self):
        root = ElementTree.parse(self.xdmf_path).getroot()
        if root.tag != "Xdmf":
            self.error(self.xdmf_path, f"root element {root.tag!r}, expected Xdmf")
            return []
        collection = root.find("Domain/Grid")
        if collection is None or collection.get("GridType") != "Collection" \
                or collection.get("CollectionType") != "Temporal":
            self.error(self.xdmf_path, "Domain/Grid is not a temporal collection")
            return []
        grids = [self.check_grid(grid) for grid in collection.findall("Grid")]
        times = [grid["time"] for grid in grids if grid["time"] is not None]
        for earlier, later in zip(times, times[1:]):
            if not later > earlier:
                self.error(self.xdmf_path, f"time {later!r} does not follow {earlier!r}")
        return grids

    def compare(self, grids, expected_steps):
        if len(grids) != len(expected_steps):
            self.error(self.xdmf_path, f"{len(grids)} grids, expected {len(expected_steps)}")
        for index, (found, expected) in enumerate(zip(grids, expected_steps)):
            where = f"grid {index}"
            if found["time"] is None or not same_bits(np.float64(found["time"]), np.float64(expected["time"])):
                self.error(where, f"time {found['time']!r}, expected {expected['time']!r}")
            for key in ("topology", "elements"):
                if found.get(key) != expected[key]:
                    self.error(where, f"{key} {found.get(key)!r}, expected {expected[key]!r}")
            self.compare_array(f"{where} geometry", found.get("geometry"), expected["geometry"])
            if "connectivity" in expected:
                self.compare_array(f"{where} connectivity", found.get("connectivity"), expected["connectivity"])
            if set(found["attributes"]) != set(expected["attributes"]):
                self.error(where, f"attributes {sorted(found['attributes'])}, "
                                  f"expected {sorted(expected['attributes'])}")
            for name, want in expected["attributes"].items():
                have = found["attributes"].get(name)
                if have is None:
                    continue
                if have["center"] != want["center"]:
                    self.error(f"{where} {name}", f"center {have['center']!r}, expected {want['center']!r}")
                self.compare_array(f"{where} {name}", have["values"], want)

    def compare_array(self, where, found, expected):
        if found is None:
            return  # already reported
        want = np.array(expected["values"], dtype=found.dtype).reshape(expected["shape"])
        if found.shape != want.shape:
            self.error(where, f"shape {found.shape}, expected {want.shape}")
        elif not same_bits(found, want):
            index = first_difference(found, want)
            differing = int(np.count_nonzero(~bitwise_equal(found, want)))
            self.error(where, f"{differing} of {found.size} values differ from the expected ones "
                              f"(first at flat index {index}: {found.flat[index]!r}, "
                              f"expected {want.flat[index]!r})")


def bitwise_equal(a, b):
    """Element-wise equality of the bits: -0.0 differs from 0.0, a NaN equals the same NaN."""
    return a.view(f"u{a.dtype.itemsize}") == b.view(f"u{b.dtype.itemsize}")


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and bool(np.all(bitwise_equal(a, b)))


def first_difference(a, b):
    return int(np.flatnonzero(~bitwise_equal(a, b).ravel())[0])


def main(arguments):
    if len(arguments) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    checker = SeriesChecker(arguments[1])
    grids = checker.check_document()
    if len(arguments) == 3:
        with open(arguments[2], encoding="utf-8") as expected_file:
            checker.compare(grids, json.load(expected_file)["steps"])
    for h5_file in checker.h5_files.values():
        h5_file.close()
    if checker.errors:
        print(f"{arguments[1]}: {len(checker.errors)} problem(s):", file=sys.stderr)
        for message in checker.errors:
            print(f"  {message}", file=sys.stderr)
        return 1
    print(f"{arguments[1]}: {len(grids)} snapshots checked" + (" against the expected data" if len(arguments) == 3 else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
