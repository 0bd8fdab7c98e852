#pragma once
// Reader of STL wall meshes, ASCII and binary, into a TriangleMesh with shared
// vertices.
//
// Format detection is by content, not by extension: a file whose size is exactly
// 84 + 50 n bytes, n the little-endian uint32 at byte 80, is binary, even when its
// 80-byte header starts with "solid" (several exporters write that); otherwise a file
// starting with "solid" is ASCII; anything else is reported as neither.
//
// Vertex merging is exact: vertices with bit-for-bit equal coordinates (after
// reading; −0 equals +0) become one. STL repeats each shared vertex verbatim in every
// facet that uses it (the same float32 in binary, the same text in ASCII as written by
// one exporter), so exact matching recovers the topology without a tolerance. A
// tolerance would be order-dependent (merging is not transitive) and could fuse
// distinct vertices of fine features; a mesh whose copies genuinely differ is broken
// and shows up as open edges in check_topology().
//
// Facet normals stored in the file are ignored (many exporters write zeros): the
// orientation is the vertex order, right-hand rule, as in the STL specification.
//
// Errors raise tankfsi::ConfigError naming the file and the line (ASCII) or the byte
// offset and triangle index (binary): unreadable file, truncated or oversized binary,
// unexpected ASCII keyword or end of file, non-numeric or non-finite coordinate, no
// triangles at all.
#include <filesystem>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

[[nodiscard]] TriangleMesh read_stl(const std::filesystem::path& file);

}  // namespace tankfsi::sph
