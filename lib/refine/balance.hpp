#pragma once
// 2:1 balance of refinement flags (thesis §2.5, Fig. 2.2): neighbouring cells may differ by at
// most one level of refinement across a face.
//
// Levels are not stored anywhere; they are read off the geometry (refine/cell_edges.hpp). A
// flagged cell with a FINE edge (half of a coarser neighbour's edge) would, once split, put four
// faces along that neighbour's edge; the neighbour must then be split too. This is the only
// configuration that breaks the balance: splitting next to a conforming edge creates a legal 2:1
// hanging node, splitting a COARSE edge's cell reuses its hanging node and makes the edge
// conforming again. The rule is applied until nothing changes (a cell's forced split can force
// its own coarser neighbours, and so on), which terminates because each step flags a new cell.
#include <vector>

#include "refine/cell_edges.hpp"

namespace quadapt {

/// Extends `flags` (#cells, nonzero = split) in place so that splitting exactly the flagged cells
/// leaves every face conforming or 2:1. Returns the number of cells flagged by the balancing.
/// Deterministic: the result does not depend on the order in which cells are visited (it is
/// the smallest flag set containing the input that satisfies the rule).
int balance_flags(const CellEdges& edges, std::vector<char>& flags);

/// True when splitting the flagged cells keeps the 2:1 rule (no flagged cell has a FINE edge
/// towards an unflagged cell).
bool flags_balanced(const CellEdges& edges, const std::vector<char>& flags);

}  // namespace quadapt
