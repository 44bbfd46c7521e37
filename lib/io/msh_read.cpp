// read_msh: Gmsh MSH 4.1 and 2.2, ASCII and binary -> Mesh (see io/msh.hpp for the contract).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <istream>
#include <map>
#include <limits>
#include <set>
#include <sstream>
#include <unordered_map>

#include "core/atomic_file.hpp"
#include "io/gll_scheme.hpp"
#include "io/msh.hpp"
#include "io/msh_cursor.hpp"
#include "mesh/boundary.hpp"
#include "mesh/curved.hpp"

namespace quadapt {

using msh_detail::Cursor;

namespace {

/// Nodes per element of the MSH types we read or skip; -1 for types we refuse.
int nodes_of_type(long long type) {
  switch (type) {
    case 1: return 2;    // 2-node line
    case 2: return 3;    // 3-node triangle
    case 3: return 4;    // 4-node quadrangle
    case 10: return 9;   // 9-node quadrangle (order 2)
    case 36: return 16;  // 16-node quadrangle (order 3)
    case 37: return 25;  // 25-node quadrangle (order 4)
    case 38: return 36;  // 36-node quadrangle (order 5)
    case 47: return 49;  // 49-node quadrangle (order 6)
    case 15: return 1;   // point
    case 8: return 3;    // 3-node line (boundary edge of a curved mesh)
    case 26: return 4;   // 4-node line
    case 27: return 5;   // 5-node line
    case 28: return 6;   // 6-node line
    case 62: return 7;   // 7-node line
    default: return -1;
  }
}

std::string type_description(long long type) {
  switch (type) {
    case 4: return "4-node tetrahedron";
    case 5: return "8-node hexahedron";
    case 6: return "6-node prism";
    case 7: return "5-node pyramid";
    case 9: return "6-node triangle";
    case 10: return "9-node quadrangle";
    case 16: return "8-node quadrangle";
    case 21: return "10-node triangle";
    case 36: return "16-node quadrangle";
    case 37: return "25-node quadrangle";
    case 38: return "36-node quadrangle";
    case 47: return "49-node quadrangle";
    default: return "type " + std::to_string(type);
  }
}

struct RawLine {
  int a, b;
  long long phys, entity;
};

enum class ViewKind { Node, Element, ElementNode };

struct RawView {
  ViewKind kind;
  std::string name, scheme;
  long long step = 0;
  int ncomp = 1;
  std::vector<long long> tags;
  std::vector<int> mult;
  std::vector<size_t> offset;
  std::vector<double> values;
};

class MshReader {
 public:
  MshReader(const std::string& buf, const std::string& path) : c_(buf, path), size_(buf.size()) {}

  Mesh read() {
    if (c_.at_end()) c_.fail("empty file (not a Gmsh MSH file)");
    const std::string_view first = c_.token("$MeshFormat");
    if (first == "$NOD" || first == "$PTS")
      c_.fail("an MSH 1 file (it starts with " + std::string(first) + "): quadapt reads MSH 4.1 and 2.2; save it again "
              "from Gmsh with -format msh41 (or Mesh.MshFileVersion = 4.1)");
    if (first != "$MeshFormat") c_.fail("not a Gmsh MSH file (it does not start with $MeshFormat)");
    c_.section = "MeshFormat";
    read_format();
    while (!c_.at_end()) {
      c_.section.clear();
      std::string_view t = c_.token("section");
      if (t.empty() || t[0] != '$')
        c_.fail("unexpected text '" + std::string(t.substr(0, 40)) + "' between sections (malformed file)");
      const std::string name(t.substr(1));
      c_.section = name;
      if (name == "PhysicalNames") read_physical_names();
      else if (name == "Entities" && major_ == 4) read_entities();
      else if (name == "PartitionedEntities" && major_ == 4) read_partitioned_entities();
      else if (name == "Nodes") major_ == 4 ? read_nodes4() : read_nodes2();
      else if (name == "Elements") major_ == 4 ? read_elements4() : read_elements2();
      else if (name == "NodeData") read_view(ViewKind::Node);
      else if (name == "ElementData") read_view(ViewKind::Element);
      else if (name == "ElementNodeData") read_view(ViewKind::ElementNode);
      else if (name == "InterpolationScheme") read_interpolation_scheme();
      else if (name == "FrameConvention") read_frame_convention();
      else if (name == "SolvedCase") read_solved_case();
      else if (name.rfind("End", 0) == 0) c_.fail("unexpected $" + name + " (section without a start)");
      else c_.skip_section(name);
    }
    c_.section.clear();
    if (!have_nodes_) c_.fail("missing $Nodes section");
    if (!have_elements_) c_.fail("missing $Elements section");
    check_plane();
    if (quad_order_ > 1) finish_curved();
    build_groups();
    build_fields();
    complete_boundary(m_);
    return std::move(m_);
  }

 private:
  Cursor c_;
  size_t size_;
  int major_ = 0;
  bool have_nodes_ = false, have_elements_ = false;
  std::vector<std::pair<long long, std::string>> curve_names_;  // dim-1 physical names, in order
  std::map<long long, std::string> surface_names_;
  std::map<std::pair<int, long long>, long long> entity_phys_;  // (dim, entity) -> first physical tag
  std::map<long long, std::vector<long long>> curve_extra_phys_;  // curve entity -> its other physical tags
  double z_lo_ = std::numeric_limits<double>::infinity(), z_hi_ = -std::numeric_limits<double>::infinity();
  static constexpr long long kInterface = std::numeric_limits<long long>::min();
  std::map<std::pair<int, long long>, long long> partition_parent_;  // (dim, piece) -> parent tag, or kInterface
  std::unordered_map<long long, int> node_index_;
  std::unordered_map<long long, int> cell_index_;
  std::vector<long long> cell_tags_;
  std::vector<RawLine> lines_;
  int quad_order_ = 0;                   // geometric order of the quads (0: none yet)
  std::vector<int> ho_nodes_;            // curved: per cell (q+1)^2 node indices, lexicographic
  long long domain_phys_ = 0;
  bool domain_seen_ = false;
  std::vector<RawView> views_;
  Mesh m_;

  /// A header's count that disagrees with what the section lists is a damaged file (it used to be
  /// read as the section says): "the header says 20 nodes, but the blocks list 9".
  void check_header(long long header, long long listed, const std::string& noun, const char* lists = "the blocks list") {
    if (header != listed)
      c_.fail("the header says " + std::to_string(header) + " " + noun + ", but " + lists + " " + std::to_string(listed));
  }

  /// [lo, hi] grown by the tag of the `listed`-th item (the first one sets it).
  static void widen(long long& lo, long long& hi, long long listed, long long tag) {
    lo = listed == 0 ? tag : std::min(lo, tag);
    hi = listed == 0 ? tag : std::max(hi, tag);
  }

  /// A 4.1 header's smallest and largest tag must be those of the tags the section lists, [lo, hi]
  /// (only when it lists any: our writer and Gmsh write 0 0 for none). A tag outside the header's
  /// range, and a header whose minimum exceeds its maximum, fail here.
  void check_tag_range(long long min_tag, long long max_tag, long long lo, long long hi, long long listed,
                       const std::string& noun) {
    if (listed > 0 && (min_tag != lo || max_tag != hi))
      c_.fail("the header says " + noun + " tags " + std::to_string(min_tag) + " to " + std::to_string(max_tag) +
              ", but the blocks list tags " + std::to_string(lo) + " to " + std::to_string(hi));
  }

  /// A count that cannot exceed what the rest of the file could hold.
  long long bounded(long long n, const char* what) {
    if (n < 0) c_.fail("invalid " + std::string(what) + " " + std::to_string(n) + " (corrupt file?)");
    if (static_cast<unsigned long long>(n) > size_)
      c_.fail(std::string(what) + " " + std::to_string(n) + " is more than the file's " + std::to_string(size_) +
              " bytes can hold: a truncated or corrupt file");
    return n;
  }

  void read_format() {
    const std::string ver(c_.token("format version"));
    const long long ftype = c_.integer("file type");
    const long long dsize = c_.integer("data size");
    if (ver == "4.1") major_ = 4;
    else if (ver == "2.2" || ver == "2.1" || ver == "2.0" || ver == "2") major_ = 2;
    else if (ver == "4" || ver == "4.0")
      c_.fail("MSH version 4.0 is not supported (use 4.1 or 2.2; convert with: gmsh FILE -save -format msh41)");
    else
      c_.fail("unsupported MSH format version '" + ver + "' (supported: 4.1 and 2.2)");
    if (ftype != 0 && ftype != 1) c_.fail("invalid file type " + std::to_string(ftype) + " (0 = ASCII, 1 = binary)");
    if (dsize != 8 && !(major_ == 4 && dsize == 4))
      c_.fail("unsupported data size " + std::to_string(dsize) + " (only 8-byte doubles)");
    c_.binary = ftype == 1;
    c_.size_bytes = static_cast<int>(dsize);
    if (c_.binary) {
      c_.begin_binary();
      std::int32_t one = c_.bin<std::int32_t>("endianness marker");
      if (one != 1) {
        c_.swap = true;
        char* b = reinterpret_cast<char*>(&one);
        std::swap(b[0], b[3]);
        std::swap(b[1], b[2]);
        if (one != 1) c_.fail("bad endianness marker in binary header");
      }
    }
    c_.expect_end("MeshFormat");
  }

  void read_physical_names() {
    const long long n = bounded(c_.integer("number of physical names"), "number of physical names");
    for (long long i = 0; i < n; ++i) {
      const long long dim = c_.integer("physical dimension");
      const long long tag = c_.integer("physical tag");
      std::string name = c_.quoted("physical name");
      if (dim == 1) curve_names_.emplace_back(tag, name);
      else if (dim == 2) surface_names_[tag] = name;
    }
    c_.expect_end("PhysicalNames");
  }

  void read_entities() {
    if (c_.binary) c_.begin_binary();
    long long num[4];
    for (auto& v : num) v = bounded(c_.any_size("number of entities"), "number of entities");
    for (int dim = 0; dim < 4; ++dim)
      for (long long i = 0; i < num[dim]; ++i) {
        const long long tag = c_.any_int("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) c_.any_real("entity coordinates");
        const long long nphys = bounded(c_.any_size("number of physical tags"), "number of physical tags");
        long long first = 0;
        for (long long k = 0; k < nphys; ++k) {
          long long p = c_.any_int("physical tag");
          if (k == 0) first = p;
          else if (dim == 1) curve_extra_phys_[tag].push_back(p);
        }
        if (dim > 0) {
          const long long nb = bounded(c_.any_size("number of bounding entities"), "number of bounding entities");
          for (long long k = 0; k < nb; ++k) c_.any_int("bounding entity tag");
        }
        entity_phys_[{dim, tag}] = first;
      }
    c_.expect_end("Entities");
  }

  // quadapt reads x and y; a planar mesh drawn in the x-z or y-z plane would read as cells of
  // zero area ("degenerate"), which hides the cause
  void check_plane() {
    if (m_.nodes.empty() || !(z_hi_ > z_lo_)) return;
    double lo[2] = {m_.nodes[0].x(), m_.nodes[0].y()}, hi[2] = {lo[0], lo[1]};
    for (const Vec2& p : m_.nodes)
      for (int d = 0; d < 2; ++d) {
        lo[d] = std::min(lo[d], p[d]);
        hi[d] = std::max(hi[d], p[d]);
      }
    for (int d = 0; d < 2; ++d)
      if (hi[d] == lo[d]) {
        std::ostringstream s;
        s << "the mesh lies in the " << (d == 0 ? "y-z" : "x-z") << " plane (" << (d == 0 ? "x" : "y") << " = " << lo[d]
          << " at every node, z from " << z_lo_ << " to " << z_hi_
          << "): quadapt reads x and y only; turn it into the x-y plane (Gmsh: Rotate, or draw it there)";
        c_.fail(s.str());
      }
  }

  // MSH 4.1 written with partitions (gmsh -part N): the elements sit on partitioned entities,
  // each a piece of a model entity of $Entities (its parent, same dimension) or an interface
  // between partitions (a parent of higher dimension). A piece is read as its parent — its
  // physical groups, and its tag where lines have no physical group — and the lines of a
  // partition interface, interior edges of the domain, are dropped.
  void read_partitioned_entities() {
    if (c_.binary) c_.begin_binary();
    c_.any_size("number of partitions");
    const long long nghost = bounded(c_.any_size("number of ghost entities"), "number of ghost entities");
    for (long long i = 0; i < nghost; ++i) {
      c_.any_int("ghost entity tag");
      c_.any_int("ghost entity partition");
    }
    long long num[4];
    for (auto& v : num) v = bounded(c_.any_size("number of partitioned entities"), "number of partitioned entities");
    for (int dim = 0; dim < 4; ++dim)
      for (long long i = 0; i < num[dim]; ++i) {
        const long long tag = c_.any_int("partitioned entity tag");
        const long long parent_dim = c_.any_int("parent dimension");
        const long long parent_tag = c_.any_int("parent tag");
        const long long np = bounded(c_.any_size("number of partitions of the entity"), "number of partitions");
        for (long long k = 0; k < np; ++k) c_.any_int("partition tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) c_.any_real("entity coordinates");
        const long long nphys = bounded(c_.any_size("number of physical tags"), "number of physical tags");
        for (long long k = 0; k < nphys; ++k) c_.any_int("physical tag");
        if (dim > 0) {
          const long long nb = bounded(c_.any_size("number of bounding entities"), "number of bounding entities");
          for (long long k = 0; k < nb; ++k) c_.any_int("bounding entity tag");
        }
        if (parent_dim < dim || parent_dim > 3)
          c_.fail("partitioned entity " + std::to_string(tag) + " of dimension " + std::to_string(dim) +
                  " has a parent of dimension " + std::to_string(parent_dim));
        partition_parent_[{dim, tag}] = parent_dim == dim ? parent_tag : kInterface;
      }
    c_.expect_end("PartitionedEntities");
  }

  void add_node(long long tag, double x, double y, double z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
      std::ostringstream s;
      s << "node " << tag << " has a non-finite coordinate (" << x << ", " << y << ", " << z << ")";
      c_.fail(s.str());
    }
    if (!node_index_.emplace(tag, m_.num_nodes()).second) c_.fail("node tag " + std::to_string(tag) + " appears twice");
    m_.nodes.emplace_back(x, y);
    z_lo_ = std::min(z_lo_, z);
    z_hi_ = std::max(z_hi_, z);
  }

  void read_nodes4() {
    have_nodes_ = true;
    if (c_.binary) c_.begin_binary();
    const long long nblocks = bounded(c_.any_size("number of node blocks"), "number of node blocks");
    const long long total = bounded(c_.any_size("number of nodes"), "number of nodes");
    const long long min_tag = c_.any_size("minimum node tag");
    const long long max_tag = c_.any_size("maximum node tag");
    m_.nodes.reserve(m_.nodes.size() + total);
    std::vector<long long> tags;
    long long listed = 0, lo = 0, hi = 0;
    for (long long b = 0; b < nblocks; ++b) {
      const long long dim = c_.any_int("entity dimension");
      c_.any_int("entity tag");
      const long long parametric = c_.any_int("parametric flag");
      const long long n = bounded(c_.any_size("number of nodes in block"), "number of nodes in block");
      tags.resize(n);
      for (auto& t : tags) t = c_.any_size("node tag");
      const int extra = parametric ? static_cast<int>(std::min<long long>(dim, 3)) : 0;
      for (long long i = 0; i < n; ++i) {
        double x = c_.any_real("node coordinates"), y = c_.any_real("node coordinates"), z = c_.any_real("node coordinates");
        for (int k = 0; k < extra; ++k) c_.any_real("parametric coordinates");
        add_node(tags[i], x, y, z);
        widen(lo, hi, listed + i, tags[i]);
      }
      listed += n;
    }
    check_header(total, listed, "nodes");
    check_tag_range(min_tag, max_tag, lo, hi, listed, "node");
    c_.expect_end("Nodes");
  }

  void read_nodes2() {
    have_nodes_ = true;
    const long long n = bounded(c_.integer("number of nodes"), "number of nodes");
    if (c_.binary) c_.begin_binary();
    m_.nodes.reserve(m_.nodes.size() + n);
    for (long long i = 0; i < n; ++i) {
      const long long tag = c_.any_int("node tag");
      double x = c_.any_real("node coordinates"), y = c_.any_real("node coordinates"), z = c_.any_real("node coordinates");
      add_node(tag, x, y, z);
    }
    c_.expect_end("Nodes");
  }

  int node(long long tag, long long elem) {
    auto it = node_index_.find(tag);
    if (it == node_index_.end())
      c_.fail("element " + std::to_string(elem) + " refers to node " + std::to_string(tag) + ", which $Nodes does not define");
    return it->second;
  }

  void add_element(long long type, long long tag, long long phys, long long entity, const long long* nodes) {
    if (type == 1 || type == 8 || type == 26 || type == 27 || type == 28 || type == 62) {
      lines_.push_back({node(nodes[0], tag), node(nodes[1], tag), phys, entity});
    } else if (type == 2 || type == 3 || type == 10 || type == 36 || type == 37 || type == 38 || type == 47) {
      Cell c;
      c.nv = type == 2 ? 3 : 4;
      for (int i = 0; i < c.nv; ++i) c.v[i] = node(nodes[i], tag);
      int order = 1;
      while (order < kMaxGeometricOrder && gmsh_quad_type(order) != type) ++order;
      if (type == 2) order = 1;
      if (quad_order_ == 0) quad_order_ = order;
      if (order != quad_order_ || (type == 2 && quad_order_ > 1))
        c_.fail("element " + std::to_string(tag) + " is a " + type_description(type) + " but earlier cells have geometric order " +
                std::to_string(quad_order_) + " (a mesh has one geometric order; curved meshes are all quads)");
      if (order > 1) {
        const std::vector<int> perm = gmsh_quad_node_order(order);
        const size_t base = ho_nodes_.size();
        ho_nodes_.resize(base + perm.size());
        for (size_t k = 0; k < perm.size(); ++k) ho_nodes_[base + perm[k]] = node(nodes[k], tag);
      }
      if (!cell_index_.emplace(tag, m_.num_cells()).second)
        c_.fail("element tag " + std::to_string(tag) + " appears twice");
      m_.cells.push_back(c);
      cell_tags_.push_back(tag);
      if (!domain_seen_) {
        domain_seen_ = true;
        domain_phys_ = phys;
      }
    }
    // points and higher-order lines: ignored
  }

  void unsupported(long long type) {
    std::string hint;  // what to change in Gmsh for the element types it makes
    if (type == 16)  // serendipity: Gmsh's incomplete second order
      hint = "; Gmsh writes it with Mesh.SecondOrderIncomplete = 1: set it to 0 for the complete (9-node) quadrangle";
    else if (type == 9 || (type >= 20 && type <= 25))  // triangles of order 2 to 5
      hint = "; curved cells must be quadrangles (Recombine Surface, then Mesh.ElementOrder), or save at order 1";
    else if ((type >= 4 && type <= 7) || (type >= 11 && type <= 14) || (type >= 17 && type <= 19))  // volumes
      hint = "; quadapt is 2D: mesh the surface only (gmsh -2)";
    c_.fail("element " + type_description(type) +
            " is not supported (quadapt reads lines, 3-node triangles and 4- to 49-node quadrangles of order 1 to 6)" + hint);
  }

  /// Curved mesh: the control points of every cell from its high-order nodes; then Mesh::nodes
  /// is reduced to the vertices (of cells and boundary lines), in file order, so that the
  /// vertex-only view of the mesh is the same as for a straight mesh.
  void finish_curved() {
    const int q = quad_order_;
    m_.curved.order = q;
    m_.curved.points.resize(ho_nodes_.size());
    for (size_t k = 0; k < ho_nodes_.size(); ++k) m_.curved.points[k] = m_.nodes[ho_nodes_[k]];
    std::vector<int> renum(m_.nodes.size(), -1);
    for (const Cell& c : m_.cells)
      for (int i = 0; i < c.nv; ++i) renum[c.v[i]] = 0;
    for (const RawLine& l : lines_) renum[l.a] = renum[l.b] = 0;
    std::vector<Vec2> kept;
    for (size_t i = 0; i < renum.size(); ++i)
      if (renum[i] == 0) {
        renum[i] = static_cast<int>(kept.size());
        kept.push_back(m_.nodes[i]);
      }
    m_.nodes = std::move(kept);
    for (Cell& c : m_.cells)
      for (int i = 0; i < c.nv; ++i) c.v[i] = renum[c.v[i]];
    for (RawLine& l : lines_) {
      l.a = renum[l.a];
      l.b = renum[l.b];
    }
  }

  void read_elements4() {
    if (!have_nodes_) c_.fail("missing $Nodes section (it must come before $Elements)");
    have_elements_ = true;
    if (c_.binary) c_.begin_binary();
    const long long nblocks = bounded(c_.any_size("number of element blocks"), "number of element blocks");
    const long long total = c_.any_size("number of elements");
    const long long min_tag = c_.any_size("minimum element tag");
    const long long max_tag = c_.any_size("maximum element tag");
    long long nodes[(kMaxGeometricOrder + 1) * (kMaxGeometricOrder + 1)];
    // the blocks up to $EndElements, whatever the header says: then the header is checked
    // against them (number of blocks, of elements, smallest and largest tag)
    long long b = 0, listed = 0, lo = 0, hi = 0;
    for (; !c_.next_is("$EndElements"); ++b) {
      const long long dim = c_.any_int("entity dimension");
      long long entity = c_.any_int("entity tag");
      const long long type = c_.any_int("element type");
      const long long n = bounded(c_.any_size("number of elements in block"), "number of elements in block");
      const int npe = nodes_of_type(type);
      if (npe < 0) unsupported(type);
      bool interface = false;  // a partition interface: its lines are interior edges
      if (auto pp = partition_parent_.find({static_cast<int>(dim), entity}); pp != partition_parent_.end()) {
        interface = pp->second == kInterface;
        entity = pp->second;
      }
      auto it = entity_phys_.find({static_cast<int>(dim), entity});
      const long long phys = it == entity_phys_.end() ? 0 : it->second;
      for (long long e = 0; e < n; ++e) {
        const long long tag = c_.any_size("element tag");
        for (int k = 0; k < npe; ++k) nodes[k] = c_.any_size("element nodes");
        if (!(interface && dim == 1)) add_element(type, tag, phys, entity, nodes);
        widen(lo, hi, listed, tag);
        ++listed;
      }
    }
    check_header(nblocks, b, "element blocks", "the section has");
    check_header(total, listed, "elements");
    check_tag_range(min_tag, max_tag, lo, hi, listed, "element");
    c_.expect_end("Elements");
  }

  void read_elements2() {
    if (!have_nodes_) c_.fail("missing $Nodes section (it must come before $Elements)");
    have_elements_ = true;
    const long long n = bounded(c_.integer("number of elements"), "number of elements");
    long long nodes[(kMaxGeometricOrder + 1) * (kMaxGeometricOrder + 1)];
    // the elements up to $EndElements, whatever the header says: then the header is checked
    long long listed = 0;
    if (!c_.binary) {
      for (; !c_.next_is("$EndElements"); ++listed) {
        const long long tag = c_.integer("element tag");
        const long long type = c_.integer("element type");
        const long long ntags = bounded(c_.integer("number of element tags"), "number of element tags");
        long long phys = 0, entity = 0;
        for (long long k = 0; k < ntags; ++k) {
          long long t = c_.integer("element tags");
          if (k == 0) phys = t;
          if (k == 1) entity = t;
        }
        const int npe = nodes_of_type(type);
        if (npe < 0) unsupported(type);
        for (int k = 0; k < npe; ++k) nodes[k] = c_.integer("element nodes");
        add_element(type, tag, phys, entity, nodes);
      }
    } else {
      c_.begin_binary();
      while (!c_.next_is("$EndElements")) {
        const long long type = c_.bin_int("element type");
        const long long count = bounded(c_.bin_int("number of elements"), "number of elements");
        const long long ntags = bounded(c_.bin_int("number of element tags"), "number of element tags");
        const int npe = nodes_of_type(type);
        if (npe < 0) unsupported(type);
        if (count == 0) c_.fail("empty binary element block (corrupt file?)");
        for (long long e = 0; e < count; ++e) {
          const long long tag = c_.bin_int("element tag");
          long long phys = 0, entity = 0;
          for (long long k = 0; k < ntags; ++k) {
            long long t = c_.bin_int("element tags");
            if (k == 0) phys = t;
            if (k == 1) entity = t;
          }
          for (int k = 0; k < npe; ++k) nodes[k] = c_.bin_int("element nodes");
          add_element(type, tag, phys, entity, nodes);
        }
        listed += count;
      }
    }
    check_header(n, listed, "elements", "the section lists");
    c_.expect_end("Elements");
  }

  void read_view(ViewKind kind) {
    RawView v;
    v.kind = kind;
    const long long ns = bounded(c_.integer("number of string tags"), "number of string tags");
    for (long long i = 0; i < ns; ++i) {
      std::string s = c_.quoted("string tag");
      if (i == 0) v.name = s;
      if (i == 1) v.scheme = s;
    }
    const long long nr = bounded(c_.integer("number of real tags"), "number of real tags");
    for (long long i = 0; i < nr; ++i) c_.real("real tag");
    const long long ni = bounded(c_.integer("number of integer tags"), "number of integer tags");
    long long ints[3] = {0, -1, -1};
    for (long long i = 0; i < ni; ++i) {
      long long t = c_.integer("integer tag");
      if (i < 3) ints[i] = t;
    }
    if (ni < 3) c_.fail("view '" + v.name + "' lacks the integer tags (time step, components, entries)");
    v.step = ints[0];
    if (ints[1] < 1 || ints[1] > 1000) c_.fail("view '" + v.name + "' has an invalid number of components " + std::to_string(ints[1]));
    v.ncomp = static_cast<int>(ints[1]);
    const long long nent = bounded(ints[2], "number of entries");
    if (c_.binary) c_.begin_binary();
    v.tags.reserve(nent);
    v.mult.reserve(nent);
    v.offset.reserve(nent);
    for (long long e = 0; e < nent; ++e) {
      const long long tag = c_.any_int("view entry tag");
      long long mult = 1;
      if (kind == ViewKind::ElementNode) mult = c_.any_int("values per element");
      if (mult < 1 || mult > 100000) c_.fail("view '" + v.name + "': invalid number of values per element " + std::to_string(mult));
      v.tags.push_back(tag);
      v.mult.push_back(static_cast<int>(mult));
      v.offset.push_back(v.values.size());
      for (long long k = 0; k < mult * v.ncomp; ++k) v.values.push_back(c_.any_real("view values"));
    }
    c_.expect_end(kind == ViewKind::Node ? "NodeData" : kind == ViewKind::Element ? "ElementData" : "ElementNodeData");
    if (kind == ViewKind::Node) return;  // node data: not a quadapt field (ignored)
    for (RawView& old : views_) {
      if (old.kind != kind || old.name != v.name) continue;
      if (v.step > old.step) {  // a later time step replaces the earlier one
        old = std::move(v);
      } else if (v.step == old.step) {  // another partition of the same step
        if (v.ncomp != old.ncomp) c_.fail("view '" + v.name + "' changes its number of components");
        for (size_t i = 0; i < v.tags.size(); ++i) {
          old.tags.push_back(v.tags[i]);
          old.mult.push_back(v.mult[i]);
          old.offset.push_back(old.values.size() + v.offset[i]);
        }
        old.values.insert(old.values.end(), v.values.begin(), v.values.end());
      }
      return;
    }
    views_.push_back(std::move(v));
  }

  void read_frame_convention() {
    const std::string_view t = c_.token("frame convention");
    if (t.empty() || t[0] == '$') c_.fail("empty $FrameConvention section");
    m_.frame_convention = std::string(t);
    c_.expect_end("FrameConvention");
  }

  void read_solved_case() {
    std::string t = c_.line("solved case");
    if (t.empty() || t[0] == '$') c_.fail("empty $SolvedCase section");
    m_.solved_case = std::move(t);
    c_.expect_end("SolvedCase");
  }

  void read_interpolation_scheme() {
    c_.quoted("scheme name");
    const long long ntop = bounded(c_.integer("number of element topologies"), "number of element topologies");
    for (long long t = 0; t < ntop; ++t) {
      c_.integer("element topology");
      const long long nmat = bounded(c_.integer("number of interpolation matrices"), "number of matrices");
      for (long long k = 0; k < nmat; ++k) {
        const long long rows = bounded(c_.integer("matrix rows"), "matrix rows");
        const long long cols = bounded(c_.integer("matrix columns"), "matrix columns");
        for (long long i = 0; i < rows * cols; ++i) c_.real("matrix entry");
      }
    }
    c_.expect_end("InterpolationScheme");
  }

  /// "7 ('outflow')" / "7" for messages.
  std::string physical_label(long long tag) const {
    for (const auto& [t, name] : curve_names_)
      if (t == tag) return std::to_string(tag) + " ('" + name + "')";
    return std::to_string(tag);
  }

  /// A physical tag is stored as an int (Mesh::BoundaryGroup::tag, domain_tag): one beyond
  /// 1..INT_MAX is refused, not wrapped (a tag 2^31 + 5 became -2147483643).
  void check_physical_tag(long long tag, const char* what) const {
    if (tag < 1 || tag > std::numeric_limits<int>::max())
      c_.fail(std::string(what) + " " + std::to_string(tag) + " is out of range (1.." +
              std::to_string(std::numeric_limits<int>::max()) + "): renumber the physical group");
  }

  /// quadapt gives each boundary edge one group: a curve in two physical groups (4.1: an entity
  /// with two tags; 2.2: the same line written once per group) would silently lose one of them —
  /// a Dirichlet condition or the functional's boundary. Refused, naming both. A line written
  /// twice in one group is one boundary edge: the repeats are dropped from lines_.
  void one_group_per_edge() {
    for (const RawLine& l : lines_) {
      auto it = curve_extra_phys_.find(l.entity);
      if (l.phys != 0 && it != curve_extra_phys_.end())
        c_.fail("curve " + std::to_string(l.entity) + " is in physical groups " + physical_label(l.phys) + " and " +
                physical_label(it->second.front()) +
                ": quadapt gives each boundary edge one group; keep one Physical Curve per curve");
    }
    // group key of a line: (0, physical tag) or, without one, (1, entity tag) — a pair, not a
    // signed tag: negating an entity tag overflowed at the most negative value (fuzzer, UBSan)
    using GroupKey = std::pair<int, long long>;
    std::map<std::pair<int, int>, GroupKey> seen;  // sorted end nodes -> group key of the first line
    std::vector<RawLine> kept;
    kept.reserve(lines_.size());
    for (const RawLine& l : lines_) {
      const auto key = std::minmax(l.a, l.b);
      const GroupKey group = l.phys != 0 ? GroupKey{0, l.phys} : GroupKey{1, l.entity};
      auto [it, fresh] = seen.emplace(key, group);
      if (fresh) {
        kept.push_back(l);
      } else if (it->second != group) {
        const auto label = [&](const GroupKey& g) {
          return g.first == 0 ? "physical group " + physical_label(g.second) : "curve " + std::to_string(g.second);
        };
        std::ostringstream e;
        e.precision(6);
        e << "the boundary edge (" << m_.nodes[l.a].x() << ", " << m_.nodes[l.a].y() << ") - (" << m_.nodes[l.b].x()
          << ", " << m_.nodes[l.b].y() << ") is in " << label(it->second) << " and in " << label(group)
          << " (one curve in two physical groups?): quadapt gives each boundary edge one group; keep one Physical "
             "Curve per curve";
        c_.fail(e.str());
      }
    }
    lines_ = std::move(kept);
  }

  void build_groups() {
    one_group_per_edge();
    // Boundary groups: declared dim-1 physical names first, then unnamed keys in file order.
    std::map<std::pair<int, long long>, int> group_of;  // (0 = physical, 1 = entity), tag
    std::vector<char> by_entity;
    for (const auto& [tag, name] : curve_names_) {
      check_physical_tag(tag, "physical tag");
      if (group_of.count({0, tag})) continue;
      group_of[{0, tag}] = static_cast<int>(m_.groups.size());
      m_.groups.push_back({static_cast<int>(tag), name});
      by_entity.push_back(0);
    }
    for (const RawLine& l : lines_) {
      std::pair<int, long long> k = l.phys != 0 ? std::make_pair(0, l.phys) : std::make_pair(1, l.entity);
      auto it = group_of.find(k);
      int g;
      if (it == group_of.end()) {
        if (k.first == 0) check_physical_tag(k.second, "the physical tag of a boundary line");
        g = static_cast<int>(m_.groups.size());
        group_of[k] = g;
        // an entity tag beyond an int gets a free tag below (t <= 0)
        const bool fits = k.second >= 1 && k.second <= std::numeric_limits<int>::max();
        m_.groups.push_back({fits ? static_cast<int>(k.second) : 0, ""});
        by_entity.push_back(k.first == 1);
      } else {
        g = it->second;
      }
      m_.boundary.push_back({{l.a, l.b}, g});
    }
    // Names for unnamed groups: the unit square's side they lie on, else boundary_<tag>.
    const bool square = is_unit_square(m_);
    std::vector<std::string> side(m_.groups.size());
    std::vector<char> one_side(m_.groups.size(), 1);
    for (const BoundaryEdge& be : m_.boundary) {
      std::string s = unit_square_side(m_.nodes[be.v[0]], m_.nodes[be.v[1]]);
      if (side[be.group].empty() && one_side[be.group]) side[be.group] = s;
      if (s.empty() || s != side[be.group]) one_side[be.group] = 0;
    }
    // Several unnamed groups on one side (a side made of two curves in a file without physical
    // groups) all take the side's name: merged into the first (before, the second became
    // boundary_<tag>, and a case's "left" covered half of x = 0).
    // A side name declared in $PhysicalNames that no line carries (Gmsh's MSH 2.2 with
    // Mesh.SaveAll writes physical tag 0 on every element) takes the unnamed groups on its side
    // too: before, 'right' stayed empty beside boundary_2 and the case's 'right' was refused.
    // Only in that signature (names declared, no line with a physical tag): a name declared for
    // a curve that lost its tag while the others kept theirs stays refused by the case check.
    std::vector<int> merged_into(m_.groups.size(), -1);
    const bool save_all_22 = std::none_of(lines_.begin(), lines_.end(), [](const RawLine& l) { return l.phys != 0; });
    std::map<std::string, int> side_group;  // side name -> the group that took it
    for (size_t g = 0; g < m_.groups.size(); ++g) {
      if (!m_.groups[g].name.empty()) continue;
      std::string name;
      if (square && one_side[g] && !side[g].empty()) {
        const int named = m_.find_group(side[g]);
        if (named < 0) {
          name = side[g];
          side_group[name] = static_cast<int>(g);
        } else if (auto it = side_group.find(side[g]); it != side_group.end()) {
          merged_into[g] = it->second;
          m_.groups[g].name = side[g];  // (removed below)
          continue;
        } else if (save_all_22 && !by_entity[named]) {  // a declared name: no line carries it
          side_group[side[g]] = named;
          merged_into[g] = named;
          m_.groups[g].name = side[g];  // (removed below)
          continue;
        }
      }
      if (name.empty()) {
        name = "boundary_" + std::to_string(m_.groups[g].tag);
        for (int k = 2; m_.find_group(name) >= 0; ++k) name = "boundary_" + std::to_string(m_.groups[g].tag) + "_" + std::to_string(k);
      }
      m_.groups[g].name = name;
    }
    if (std::any_of(merged_into.begin(), merged_into.end(), [](int t) { return t >= 0; })) {
      std::vector<int> index(m_.groups.size());
      std::vector<BoundaryGroup> kept;
      std::vector<char> kept_by_entity;
      for (size_t g = 0; g < m_.groups.size(); ++g)
        if (merged_into[g] < 0) {
          index[g] = static_cast<int>(kept.size());
          kept.push_back(m_.groups[g]);
          kept_by_entity.push_back(by_entity[g]);
        }
      for (size_t g = 0; g < m_.groups.size(); ++g)
        if (merged_into[g] >= 0) index[g] = index[merged_into[g]];
      for (BoundaryEdge& be : m_.boundary) be.group = index[be.group];
      m_.groups = std::move(kept);
      by_entity = std::move(kept_by_entity);
    }
    // Entity-keyed groups keep the entity tag as physical tag unless a physical group has it.
    std::set<int> used;
    for (size_t g = 0; g < m_.groups.size(); ++g)
      if (!by_entity[g]) used.insert(m_.groups[g].tag);
    for (size_t g = 0; g < m_.groups.size(); ++g) {
      if (!by_entity[g]) continue;
      int t = m_.groups[g].tag;
      if (t <= 0 || used.count(t)) {
        if (used.empty()) t = 1;
        else if (*used.rbegin() < std::numeric_limits<int>::max()) t = *used.rbegin() + 1;
        else for (t = 1; used.count(t); ++t) {}  // the largest is INT_MAX (a file may say so)
      }
      m_.groups[g].tag = t;
      used.insert(t);
    }
    if (domain_phys_ != 0) {
      check_physical_tag(domain_phys_, "the physical tag of the surface");
      m_.domain_tag = static_cast<int>(domain_phys_);
      auto it = surface_names_.find(domain_phys_);
      if (it != surface_names_.end()) m_.domain_name = it->second;
    }
  }

  void build_fields() {
    for (const RawView& v : views_) {
      const std::string what = "view '" + v.name + "'";
      std::unordered_map<long long, size_t> entry;
      entry.reserve(v.tags.size());
      for (size_t i = 0; i < v.tags.size(); ++i) entry[v.tags[i]] = i;
      std::vector<size_t> at(m_.cells.size());
      for (size_t c = 0; c < m_.cells.size(); ++c) {
        auto it = entry.find(cell_tags_[c]);
        if (it == entry.end())
          c_.fail(what + " has no value for element " + std::to_string(cell_tags_[c]) + " (every cell needs one)");
        at[c] = it->second;
      }
      if (v.kind == ViewKind::Element) {
        CellField f;
        f.name = v.name;
        f.ncomp = v.ncomp;
        f.values.reserve(m_.cells.size() * v.ncomp);
        for (size_t c = 0; c < at.size(); ++c)
          f.values.insert(f.values.end(), v.values.begin() + v.offset[at[c]], v.values.begin() + v.offset[at[c]] + v.ncomp);
        m_.set_field(std::move(f));
        continue;
      }
      CellNodeField f;
      f.name = v.name;
      f.ncomp = v.ncomp;
      f.per_cell = at.empty() ? 1 : v.mult[at[0]];
      for (size_t c = 0; c < at.size(); ++c)
        if (v.mult[at[c]] != f.per_cell)
          c_.fail(what + ": element " + std::to_string(cell_tags_[c]) + " has " + std::to_string(v.mult[at[c]]) +
                  " values, others " + std::to_string(f.per_cell));
      const int p = parse_gll_scheme_name(v.scheme);
      if (p >= 0) {
        if (f.per_cell != (p + 1) * (p + 1))
          c_.fail(what + " uses scheme " + v.scheme + " but has " + std::to_string(f.per_cell) + " values per element, not " +
                  std::to_string((p + 1) * (p + 1)));
        f.degree = p;
      }
      const size_t len = static_cast<size_t>(f.per_cell) * f.ncomp;
      f.values.reserve(m_.cells.size() * len);
      for (size_t c = 0; c < at.size(); ++c)
        f.values.insert(f.values.end(), v.values.begin() + v.offset[at[c]], v.values.begin() + v.offset[at[c]] + len);
      m_.set_field(std::move(f));
    }
  }
};

}  // namespace

Mesh read_msh(std::istream& in, const std::string& path_for_messages) {
  std::string buf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path_for_messages, "read error");
  return MshReader(buf, path_for_messages).read();
}

Mesh read_msh(const std::string& path) {
  // one way in for every file: standard input's bytes (kept for the report's sha256), a directory
  // or an unreadable file as an InputError (core/atomic_file.hpp)
  return MshReader(read_text_file(path), path == "-" ? "standard input" : path).read();
}

Mesh read_valid_msh(const std::string& path, const ValidateOptions& v) {
  Mesh m = read_msh(path);
  validate_mesh(m, path, v);
  return m;
}

}  // namespace quadapt
