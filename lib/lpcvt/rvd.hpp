#pragma once
// The restricted (clipped) Voronoi diagram: Voronoi cells of the sites intersected with the
// domain (thesis §4.3), computed as pieces  Omega_i ∩ Q  for every integration cell Q of the
// background (lpcvt/background.hpp). Since every Q is convex, each piece is a convex polygon
// obtained by clipping Q with the half-planes of site i's Voronoi cell (Sutherland-Hodgman
// with the convex cell as clipper, as in [132]). Because the integration cells tile Omega, the
// pieces tile the clipped Voronoi diagram for ANY polygonal domain, convex or not, with holes.
//
// Enumeration: for every Q, start at the site nearest to Q's centroid (its cell meets Q), clip,
// and continue breadth-first with the Delaunay neighbours j whose bisector appears as an edge
// of the clipped polygon: the cells meeting a convex Q are connected. Every piece is met once.
//
// Speed: for a site off the convex hull of the sites the Voronoi polygon is known from the
// Delaunay triangulation (the circumcentres around it, delaunay.hpp), so its piece is that
// polygon clipped by Q's edges — and most polygons lie inside one Q, where nothing is clipped.
// Sites on the hull (unbounded cells) start from Q and are clipped by their bisectors.
//
// Each polygon edge carries a label: the bisector with site j (label j >= 0) or edge e of Q
// (label -1 - e). Vertex k is the intersection of the lines of edges k-1 and k, which is what
// the gradient needs (lpcvt/energy.hpp): a Q vertex (constant), a bisector/Q-edge intersection
// (a "clip point", depends on x_i, x_j), or a bisector/bisector intersection (a Voronoi vertex,
// the circumcentre of x_i, x_j, x_k).
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "lpcvt/background.hpp"
#include "lpcvt/cell_grid.hpp"
#include "lpcvt/delaunay.hpp"
#include "lpcvt/metric_graph.hpp"
#include "lpcvt/site_tree.hpp"

namespace quadapt::lpcvt {

/// A convex polygon piece of the clipped Voronoi cell of `site` inside integration cell `cell`.
struct RvdPiece {
  int site = -1;
  int cell = -1;
  std::vector<Vec2> v;     ///< vertices, counter-clockwise
  std::vector<int> label;  ///< label[k] of the edge v[k] -> v[k+1]: site j, or -1 - (edge of Q)
};

/// Per-thread scratch space for RestrictedVoronoi::pieces.
struct RvdWorkspace {
  std::vector<int> stamp;  ///< per site: the call (generation) that last visited it
  int gen = 0;             ///< generation of the current call
  std::vector<int> queue;
  std::vector<Vec2> tmp_v;
  std::vector<int> tmp_l;
  // metric cells: the sites examined for one piece (security-radius search)
  std::vector<int> seen;    ///< per site: the piece (generation) that last examined it
  int seen_gen = 0;
  std::vector<int> ring;    ///< sites to clip by (within the security radius), ascending
  CellGrid grid;            ///< the current cell's sites in buckets (cell_grid.hpp), when it has many
  std::vector<int> cand;    ///< the grid's candidates for one piece
  long grid_builds = 0, grid_searches = 0;  ///< grids built / security searches answered by one
  // the last box query of each site (security_candidates): valid for one RestrictedVoronoi
  long box_owner = 0;               ///< its id
  int box_epoch = 0;
  std::vector<int> box_gen;         ///< per site: the epoch of its cached box
  std::vector<Vec2> box_ext;        ///< per site: the box's half extents around the site
  std::vector<std::array<int, 2>> box_at;  ///< per site: offset and length in box_sites
  std::vector<int> box_sites;       ///< the boxes' sites, one after another
  std::vector<Vec2> box_d;          ///< ... and their offsets x_j - x_i from the box's site (read in
                                    ///< order: the distance test touches no site's memory)
  long box_queries = 0, box_hits = 0;  ///< site-tree queries made / answered from a cached box
  long ellipse_queries = 0;  ///< searches answered by an ellipse query of the site tree (set_ellipse_ratio)
};

class RestrictedVoronoi {
 public:
  /// Builds the Delaunay graph of `sites` (neighbours only) and the starting site of every
  /// integration cell.
  RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites);
  /// With the Delaunay graph of `sites` given (built with with_voronoi; kept alive by the caller).
  RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites, const DelaunayGraph& dt);
  /// Metric cells (bg.metric_cells(), metric_graph.hpp): the neighbours are those of `mg` (the
  /// metric Delaunay graph of `sites`, kept alive by the caller) and every piece is Q clipped by
  /// the G_Q-bisectors of its neighbours. `dt` serves the start sites.
  RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites, const DelaunayGraph& dt,
                    const MetricGraph* mg);
  /// Metric cells without a Delaunay graph (e.g. `mg` carried by update_metric_graph): the start
  /// site of every integration cell from `start_guess` (any site per cell, e.g. the last
  /// evaluation's starts(); the same starts result), refined as always. delaunay() is not available.
  /// `tree`: a site tree of `sites` (e.g. the last evaluation's refitted by SiteTree::refit; kept
  /// alive by the caller), else one is built. The same pieces, bit for bit, either way: the
  /// security searches' sites are clipped in ascending index order, whatever tree (or grid)
  /// lists them.
  RestrictedVoronoi(const Background& bg, const std::vector<Vec2>& sites, const MetricGraph& mg,
                    std::vector<int> start_guess, const SiteTree* tree = nullptr);

  const DelaunayGraph& delaunay() const { return *dt_; }
  /// Per integration cell: the site nearest to its centroid in G_Q (-1: none).
  const std::vector<int>& starts() const { return start_; }
  const std::vector<Vec2>& sites() const { return *sites_; }

  /// The non-empty pieces inside integration cell q, in breadth-first order from the start
  /// site (deterministic), written to out[0..count); returns count. `out` grows as needed and
  /// never shrinks, so the pieces' vertex buffers are reused between calls (no allocation once
  /// warm). Thread-safe (const) with one workspace and one `out` per thread.
  int pieces(int q, std::vector<RvdPiece>& out, RvdWorkspace& ws) const;

  /// All pieces of all cells (serial; for pictures and tests), ordered by cell; with `ws`, that
  /// workspace (its counters) instead of a local one.
  std::vector<RvdPiece> all_pieces(RvdWorkspace* ws = nullptr) const;
  /// Metric cells: an integration cell that holds about `min_sites` sites or more (its metric
  /// area over the first piece's) answers its security-radius searches from a bucket grid in
  /// its metric space (cell_grid.hpp) instead of the site tree; 0: always the tree. The same
  /// pieces, bit for bit, either way.
  void set_grid_min_sites(int min_sites) { grid_min_sites_ = min_sites; }
  static constexpr int kGridMinSites = 32;  ///< the default (energy.hpp's EnergySettings too)
  /// Metric cells, a search the grid does not answer: where the axis-aligned box of the
  /// security ellipse is more than `ratio` times the ellipse's area (a thin ellipse oblique to
  /// the axes), the site tree is asked for the ellipse itself (SiteTree::query_ellipse, no
  /// cache) instead of the box (security_candidates). The same pieces, bit for bit, either way.
  void set_ellipse_ratio(double ratio) { ellipse_ratio_ = ratio; }
  /// The default: the box query with its cache is the faster below (measured break-even 35-94:
  /// constant 30-degree frames of stretch 100 and 300 at the default cell anisotropy 0.9);
  /// frames of stretch up to ~150 at any angle keep it.
  static constexpr double kEllipseRatio = 64;

 private:
  const Background* bg_;
  const std::vector<Vec2>* sites_;
  long id_;  ///< unique per instance (process-wide): the workspaces' box caches belong to one
  std::unique_ptr<DelaunayGraph> own_;
  std::unique_ptr<MetricGraph> own_mg_;
  const DelaunayGraph* dt_ = nullptr;
  const MetricGraph* mg_ = nullptr;
  std::unique_ptr<SiteTree> own_tree_;  ///< when no tree is given (heap: tree_ survives a move)
  const SiteTree* tree_ = nullptr;  ///< metric cells: box queries of the security-radius search
  std::vector<int> start_;
  int grid_min_sites_ = kGridMinSites;
  double ellipse_ratio_ = kEllipseRatio;
  void find_starts();  ///< per integration cell: nearest site to its centroid (in G_Q)
  /// The sites of a box around x_i with half extents at least `ext`: from the workspace's cache
  /// when this thread's last query for site i (this evaluation) covered it, else a site-tree
  /// query of kBoxMargin * ext, cached (a site's pieces in other cells mostly fit in it). A
  /// superset of the sites in x_i +- ext, in the tree's order (SiteTree::query).
  struct Candidates {
    const int* site;  ///< the sites j
    const Vec2* d;    ///< x_j - x_i
    int n;
  };
  Candidates security_candidates(int i, const Vec2& ext, RvdWorkspace& ws) const;
  static constexpr double kBoxMargin = 1.1;
};

/// The metric Delaunay graph of `sites` in bg's frame (metric_graph.hpp): the CCW triangles
/// `tris` over `sites` flipped with the metric M of the background cell at each flip
/// quadrilateral's centroid (never flipped where that centroid is outside the domain).
MetricGraph build_metric_graph(const Background& bg, const std::vector<Vec2>& sites,
                               std::vector<std::array<int, 3>> tris);

/// Carries the metric graph `g` of these sites' earlier positions to `sites` with the same flip
/// metric (metric_delaunay_update); false, g unchanged, when more than `max_inverted` triangles
/// would invert.
bool update_metric_graph(const Background& bg, const std::vector<Vec2>& sites, MetricGraph& g,
                         int max_inverted = 0);

/// The same, starting from the Delaunay triangulation `dt` (built with triangles).
MetricGraph build_metric_graph(const Background& bg, const std::vector<Vec2>& sites,
                               const DelaunayGraph& dt);

/// Clips the convex CCW polygon (v, label) by the half-plane closer to x_i than to x_j
/// (Sutherland-Hodgman); new edges get label j. Output replaces (v, label).
void clip_by_bisector(std::vector<Vec2>& v, std::vector<int>& label, const Vec2& xi,
                      const Vec2& xj, int j, std::vector<Vec2>& tmp_v, std::vector<int>& tmp_l);
/// The same with distances in the metric G (symmetric positive definite): the half-plane
/// (y - x_i)^T G (y - x_i) <= (y - x_j)^T G (y - x_j), i.e. n . y <= n . (x_i + x_j) / 2 with
/// n = G (x_j - x_i).
void clip_by_bisector(std::vector<Vec2>& v, std::vector<int>& label, const Vec2& xi,
                      const Vec2& xj, const Mat2& G, int j, std::vector<Vec2>& tmp_v,
                      std::vector<int>& tmp_l);

}  // namespace quadapt::lpcvt
