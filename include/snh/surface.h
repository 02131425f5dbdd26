// From a character's surface to simulated flesh: triangle surfaces
// (read from OBJ, PLY or STL), their voxelization into a hex8 lattice, the
// embedding of the surface in that lattice (each surface vertex follows the
// trilinear interpolation of its cell), and the deformed surface written per
// frame.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/mesh.h"

namespace snh {

struct TriangleSurface {
  Points positions;
  std::vector<int32_t> triangles;  // three vertex indices per triangle, outward normals by the right-hand rule
  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return triangles.size() / 3; }
};

// Reads .obj, .ply (ASCII and binary) and .stl (ASCII and binary); polygons
// are fanned into triangles. snh::Error naming the file and line (or byte
// offset) for malformed input.
TriangleSurface read_surface(const std::string& path);

// Writes the surface with vertex positions x (empty: its own)
// as OBJ.
void write_obj(const std::string& path, const TriangleSurface& surface, const Points& x = {});

// Coincident vertices merged: the vertices within `tolerance` of a kept one
// (taken in vertex order; the first of a cluster is kept) become that one.
// `tolerance` is relative to the bounding box's diagonal; 0 merges only
// exactly equal positions. Triangles keep their order and count.
struct WeldedSurface {
  TriangleSurface surface;         // the kept vertices (in their original order) and the renumbered triangles
  std::vector<int32_t> vertex_of;  // per original vertex: its vertex in `surface`
  size_t merged() const { return vertex_of.size() - surface.vertex_count(); }
};
WeldedSurface weld_vertices(const TriangleSurface& surface, double tolerance = 1e-7);

// What an artist's surface holds that a closed, consistently oriented
// surface does not, counted after welding (weld_vertices): the input a
// winding-number voxelization tolerates, reported so that a user can fix it.
struct SurfaceReport {
  size_t vertices = 0, triangles = 0;
  size_t welded_vertices = 0;       // vertices merged into a coincident one (UV or normal seams)
  size_t open_edges = 0;            // edges of one triangle (holes, cracks)
  size_t non_manifold_edges = 0;    // edges of more than two triangles
  size_t inconsistent_edges = 0;    // edges of two triangles that traverse them in the same direction (a flipped one)
  size_t degenerate_triangles = 0;  // triangles of zero area, or with two corners welded together
  size_t shells = 0;                // pieces connected through shared (welded) vertices
  double enclosed_volume = 0.0;     // by the divergence theorem, of the welded surface
  // One line per defect class present, each starting with the surface's
  // name; also a line for several shells and one for a negative volume.
  std::vector<std::string> warnings;
  bool closed() const { return open_edges == 0 && non_manifold_edges == 0 && inconsistent_edges == 0; }
};
// `name` (the file) starts every warning. Throws snh::Error naming it for
// malformed arrays, indices out of range and non-finite positions.
SurfaceReport surface_report(const TriangleSurface& surface, const std::string& name = "surface",
                             double weld_tolerance = 1e-7);

// Throws snh::Error unless the surface is closed and consistently oriented:
// every edge is shared by exactly two triangles that traverse it in opposite
// directions. The message counts the open edges (used by one triangle),
// non-manifold edges (more than two) and edges traversed twice in the same
// direction (a flipped triangle), and names the first few of each with
// their vertex indices and positions. Also rejects indices out of range,
// non-finite positions, and a surface whose enclosed volume is not positive
// (triangles facing inwards). Messages start with `name` (the file).
void validate_closed_surface(const TriangleSurface& surface, const std::string& name = "surface");

// The volume a closed surface encloses, by the divergence theorem:
// sum over triangles of x0 . (x1 x x2) / 6 (negative when it faces inwards).
double enclosed_volume(const TriangleSurface& surface);

// The sum of the triangles' areas.
double surface_area(const TriangleSurface& surface);

// A hex8 lattice covering a closed surface's interior.
struct Voxelization {
  Mesh lattice;                    // hex8, VTK node order, elements of one rest shape (cubes of side `cell`)
  double cell = 0.0;               // the cube side
  std::array<double, 3> origin{};  // the corner of grid cell (0, 0, 0)
  std::array<int, 3> dims{};       // grid cells per axis
  // Per element: its grid cell (i, j, k); the cube spans origin + cell * [i, i+1] x ...
  std::vector<std::array<int, 3>> element_cell;
  // Pieces of the lattice (elements connected through shared vertices): 1
  // for a connected shape; more where parts touch only across a cut or
  // along a cell edge or corner (see voxelize).
  int components = 0;
  // The surface's defects (surface_report) and one line per defect class,
  // naming the file (VoxelizeOptions::name); empty for a clean surface.
  SurfaceReport report;
  std::vector<std::string> warnings;
};

struct VoxelizeOptions {
  // The grid (dims product) may hold at most this many cells; a larger one
  // is refused with a message naming its size, before anything is allocated.
  int64_t max_grid_cells = int64_t(1) << 26;
  // Also keep every cell the surface passes through (its triangles meet the
  // cube's interior), whatever its centre: the lattice then covers the whole
  // solid and every surface point lies in a kept cell (the embedding needs
  // no extrapolation), at the price of a layer of cells that stick out by
  // up to a cell. A gap thinner than a cell stays open where no cell centre
  // lies in it; a cell whose centre is in the gap is kept and glues its
  // two sides (see voxelize).
  bool cover_surface = false;
  // Refuse any surface that is not closed and consistently oriented
  // (validate_closed_surface) and decide inside by crossing counts, as the
  // voxelizer did before it took winding numbers. Off: artist surfaces with
  // seams, holes, non-manifold edges or several (intersecting) shells are
  // voxelized by their generalized winding number, their defects warned.
  bool strict = false;
  // Vertices closer than this times the bounding box's diagonal are one
  // (weld_vertices) before the surface is checked and voxelized.
  double weld_tolerance = 1e-7;
  // Accuracy of the hierarchical winding number (fast_winding_number): a
  // cluster of triangles is summarized when the query is farther than beta
  // times its radius from its centre.
  double winding_beta = 2.0;
  // The surface's file, to name it in errors and warnings.
  std::string name = "surface";
};

// The grid: dims[d] = ceil(extent_d / cell) (at least 1; an extent a
// rounding error above a multiple of the cell takes no extra cell) cubes of
// side `cell` per axis from the bounding box's lowest corner (a box-shaped
// surface whose sides are multiples of the cell is filled exactly).
//
// First the surface is welded (weld_vertices with options.weld_tolerance)
// and its defects counted (surface_report; Voxelization::warnings), unless
// options.strict, which requires it closed as given.
//
// Which cells: a grid cell becomes an element when its centre is inside the
// surface: its generalized winding number is at least 1/2 (Jacobson et al.
// 2013; evaluated hierarchically with accuracy options.winding_beta, Barill
// et al. 2018): 1 inside a closed surface, 2 where shells overlap, about
// 1/2 across a hole, so that seams, holes, non-manifold edges and several
// or intersecting shells give the solid a user means. On a watertight
// surface this keeps the same cells as the crossing count below, except a
// centre within rounding of the surface (where the winding number is 1/2).
// With cover_surface, also when a triangle meets the open cube (separating
// axes, Akenine-Moeller 2001, on the cube shrunk by 1e-9 cells, so that a
// cell the surface only touches along its boundary stays out).
// With options.strict the winding number is instead counted along rays
// parallel to +x from every cell centre, crossing by crossing (positive:
// inside), with exact tie handling: a ray through a triangle's edge or
// vertex is decided as if moved by an infinitesimal (0, e, e^2), each edge
// evaluated once in a fixed vertex order so that the triangles sharing it
// agree, and a centre lying exactly on the surface as if moved by +x.
//
// How cells connect (thin gaps, the paper's non-manifold lattices): two
// face-adjacent elements share the 4 vertices of their common face only when
// the segment between their centres does not cross the surface (counted as
// above, along that axis); otherwise each keeps its own copies, so the two
// sides of a slit thinner than a cell are not glued. Cells kept by
// cover_surface with their centre outside are glued to their neighbours
// whatever the segment crosses (the surface passes through them by
// definition); only two cells with both centres inside can be kept apart. Lattice vertices are the
// classes of element corners joined through shared faces (union-find):
// elements that touch only along an edge or at a corner share those
// vertices only when a chain of face-sharing elements around that edge or
// corner joins them; otherwise they get separate vertices (the piece then
// counts as its own component).
//
// Throws snh::Error, starting with options.name, for a surface without
// triangles, with non-finite coordinates or indices out of range, with
// options.strict one that is not closed (validate_closed_surface), for
// cell <= 0, or a lattice that would be empty (nothing enclosed) or too
// large.
Voxelization voxelize(const TriangleSurface& surface, double cell, const VoxelizeOptions& options = {});

// Each surface vertex's element and its 8 trilinear weights (hex8 node
// order), so that the surface follows the lattice.
struct Embedding {
  std::vector<int32_t> element;  // per surface vertex
  std::vector<double> weights;   // 8 per surface vertex, summing to 1
};

// Each vertex goes to the nearest element (grid cell) by its distance to the
// closed cube, distances below 1e-9 cells counting as 0; ties (a vertex on a
// face, edge or corner shared by elements) go to the cell with the smallest
// grid index i + dims[0] (j + dims[1] k). A vertex outside every element (the
// centre-inside rule drops cells the surface passes through) is extrapolated
// from its nearest element: its weights are that cell's trilinear functions
// at its unclamped local coordinates (still summing to 1), so the surface is
// reproduced exactly at rest and under affine maps of the lattice. Throws
// snh::Error naming a surface vertex more than one cell from every element.
Embedding embed(const Voxelization& voxels, const TriangleSurface& surface);

// Like embed, for surfaces as artists make them (open sheets, flaps thinner
// than a cell, loose points): a vertex farther than one cell from every
// element is carried too. It goes to its nearest element (ties as above),
// extended to first order from the cube's point q nearest to it: weights
// N_a(q) + grad N_a(q) . (p - q), which sum to 1, reproduce affine maps of
// the lattice exactly and grow linearly with the distance. Vertices within
// one cell are embedded exactly as embed does. distance: per vertex, its
// distance from its element (0 inside it).
struct CarriedEmbedding {
  Embedding embedding;
  std::vector<double> distance;
};
CarriedEmbedding embed_carrying_all(const Voxelization& voxels, const TriangleSurface& surface);

// The boundary of a volume mesh as a triangle surface: the element faces
// used by exactly one element (the faces write_obj_surface and
// write_ply_surface write), oriented outwards, hex8 quads split into two
// triangles (corners 0 1 2 and 0 2 3 of the face), in element order. Its
// vertices are the mesh vertices on the boundary, in mesh order, at
// positions x (per mesh vertex; empty: the rest positions). Throws
// snh::Error for a malformed mesh or positions of the wrong size.
struct MeshBoundary {
  TriangleSurface surface;
  std::vector<int32_t> vertices;  // the mesh vertex of each surface vertex
};
MeshBoundary boundary_surface(const Mesh& mesh, const Points& x = {});

// The surface's vertex positions for lattice positions x.
Points embedded_positions(const Embedding& embedding, const Mesh& lattice, const Points& x);

}  // namespace snh
