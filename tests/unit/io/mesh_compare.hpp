#pragma once
// Exact (bit-for-bit) comparison of two meshes with their fields, for the round-trip tests.
#include <doctest/doctest.h>

#include <cstring>

#include "mesh/mesh.hpp"

namespace quadapt::test {

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

inline void check_same_mesh(const Mesh& a, const Mesh& b) {
  REQUIRE(a.num_nodes() == b.num_nodes());
  REQUIRE(a.num_cells() == b.num_cells());
  for (int i = 0; i < a.num_nodes(); ++i) {
    CHECK(same_bits(a.nodes[i].x(), b.nodes[i].x()));
    CHECK(same_bits(a.nodes[i].y(), b.nodes[i].y()));
  }
  for (int c = 0; c < a.num_cells(); ++c) {
    CHECK(a.cells[c].nv == b.cells[c].nv);
    CHECK(a.cells[c].v == b.cells[c].v);
  }
  REQUIRE(a.groups.size() == b.groups.size());
  for (size_t g = 0; g < a.groups.size(); ++g) {
    CHECK(a.groups[g].name == b.groups[g].name);
    CHECK(a.groups[g].tag == b.groups[g].tag);
  }
  REQUIRE(a.boundary.size() == b.boundary.size());
  for (size_t e = 0; e < a.boundary.size(); ++e) {
    CHECK(a.boundary[e].v == b.boundary[e].v);
    CHECK(a.boundary[e].group == b.boundary[e].group);
  }
  CHECK(a.domain_name == b.domain_name);
  CHECK(a.domain_tag == b.domain_tag);
  CHECK(a.frame_convention == b.frame_convention);
  CHECK(a.solved_case == b.solved_case);
  REQUIRE(a.cell_fields.size() == b.cell_fields.size());
  for (size_t f = 0; f < a.cell_fields.size(); ++f) {
    const CellField &x = a.cell_fields[f], &y = b.cell_fields[f];
    CHECK(x.name == y.name);
    CHECK(x.ncomp == y.ncomp);
    REQUIRE(x.values.size() == y.values.size());
    size_t diff = 0;
    for (size_t i = 0; i < x.values.size(); ++i) diff += !same_bits(x.values[i], y.values[i]);
    CHECK_MESSAGE(diff == 0, "field " << x.name);
  }
  REQUIRE(a.cell_node_fields.size() == b.cell_node_fields.size());
  for (size_t f = 0; f < a.cell_node_fields.size(); ++f) {
    const CellNodeField &x = a.cell_node_fields[f], &y = b.cell_node_fields[f];
    CHECK(x.name == y.name);
    CHECK(x.ncomp == y.ncomp);
    CHECK(x.per_cell == y.per_cell);
    CHECK(x.degree == y.degree);
    REQUIRE(x.values.size() == y.values.size());
    size_t diff = 0;
    for (size_t i = 0; i < x.values.size(); ++i) diff += !same_bits(x.values[i], y.values[i]);
    CHECK_MESSAGE(diff == 0, "field " << x.name);
  }
}

}  // namespace quadapt::test
