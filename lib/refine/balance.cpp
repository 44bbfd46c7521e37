#include "refine/balance.hpp"

#include <string>

#include "core/error.hpp"

namespace quadapt {

int balance_flags(const CellEdges& edges, std::vector<char>& flags) {
  if (flags.size() != edges.size())
    throw Error("balance_flags: " + std::to_string(flags.size()) + " flags for " +
                std::to_string(edges.size()) + " cells");
  std::vector<int> work;
  for (int c = 0; c < static_cast<int>(flags.size()); ++c)
    if (flags[c]) work.push_back(c);
  int added = 0;
  while (!work.empty()) {
    const int c = work.back();
    work.pop_back();
    for (const CellEdge& e : edges[c]) {
      if (e.kind != EdgeKind::Fine) continue;
      const int n = e.neighbour[0];
      if (n >= 0 && !flags[n]) {
        flags[n] = 1;
        ++added;
        work.push_back(n);
      }
    }
  }
  return added;
}

bool flags_balanced(const CellEdges& edges, const std::vector<char>& flags) {
  for (size_t c = 0; c < edges.size(); ++c) {
    if (!flags[c]) continue;
    for (const CellEdge& e : edges[c])
      if (e.kind == EdgeKind::Fine && e.neighbour[0] >= 0 && !flags[e.neighbour[0]]) return false;
  }
  return true;
}

}  // namespace quadapt
