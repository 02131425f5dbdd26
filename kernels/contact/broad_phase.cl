/* Barrier self-contact's broad phase on the device (solver/
 * barrier_broad_phase.h): the candidate pairs of a surface's points, edges
 * and triangles at q (or swept along q + t dq, t in [0, 1]), the same set
 * and order as the host's BarrierContact::candidate_pairs, then the pairs
 * closer than dhat, compacted in order, and the index lists the pair sums
 * run through (kernels/contact/barrier_pairs.cl).
 *
 * Boxes, in one array: the query boxes, points then edges (not inflated),
 * then the grid boxes, triangles then edges (inflated by dhat). A box spans
 * its vertices at q and, swept, at q + dq, exactly as the host computes it.
 * The grid: a uniform grid over the grid boxes' bounds, its cell about the
 * mean box extent and at most 8 cells per box (as the host's); (cell, grid
 * box) entries, sorted (kernels/sort.cl), looked up by binary search. A
 * query box visits its cells and keeps a grid box that overlaps it (the
 * host's test), of the right kind (a triangle for a point, a later edge for
 * an edge), sharing no vertex and not left out at rest (a binary search in
 * the sorted exclusion keys). A pair is counted in one cell only, the one
 * holding the low corner of the two boxes' intersection, which both boxes
 * cover: no duplicates. Counted, scanned, then written per query box and
 * sorted there, so the list is sorted by (kind, a, b): pair keys kind << 62
 * | a << 31 | b, as the host's exclusion keys.
 *
 * No atomics and no floating-point sums feed a result: the grid's cell size
 * comes from a fixed-order sum, and only speed depends on it. */
#if defined(cl_khr_fp64) && !SNH_DOUBLE
#undef SNH_DOUBLE
#define SNH_DOUBLE 1
#endif
#include "snh_portable.h"

#define SNH_BROAD_SPAN 256

SNH_FN ulong broad_pair_key(const int kind, const int a, const int b) {
  return ((ulong)kind << 62) | ((ulong)a << 31) | (ulong)b;
}

/* Box i's vertices: n of them into v. */
SNH_FN int broad_box_vertices(const int i, __global const int* points, const int point_count, __global const int* edges,
                              const int edge_count, __global const int* triangles, const int triangle_count, int* v) {
  if (i < point_count) {
    v[0] = points[i];
    return 1;
  }
  int k = i - point_count;
  if (k < edge_count) {
    v[0] = edges[2 * k];
    v[1] = edges[2 * k + 1];
    return 2;
  }
  k -= edge_count;
  if (k < triangle_count) {
    v[0] = triangles[3 * k];
    v[1] = triangles[3 * k + 1];
    v[2] = triangles[3 * k + 2];
    return 3;
  }
  k -= triangle_count;
  v[0] = edges[2 * k];
  v[1] = edges[2 * k + 1];
  return 2;
}

/* Box i (query boxes then grid boxes): lo and hi, 3 each. */
__kernel void snh_broad_boxes(__global const real* q, __global const real* dq, const int swept,
                              __global const int* points, const int point_count, __global const int* edges,
                              const int edge_count, __global const int* triangles, const int triangle_count,
                              const real inflate, __global real* lo, __global real* hi) {
  const int i = get_global_id(0);
  const int queries = point_count + edge_count;
  if (i >= queries + triangle_count + edge_count) return;
  int v[3];
  const int n = broad_box_vertices(i, points, point_count, edges, edge_count, triangles, triangle_count, v);
  const real grow = i < queries ? SNH_R(0) : inflate;
  for (int d = 0; d < 3; ++d) {
    real l = q[3 * v[0] + d], h = l;
    for (int k = 0; k < n; ++k) {
      const real a = q[3 * v[k] + d];
      l = a < l ? a : l;
      h = a > h ? a : h;
      if (swept) {
        const real e = a + dq[3 * v[k] + d];
        l = e < l ? e : l;
        h = e > h ? e : h;
      }
    }
    lo[3 * i + d] = l - grow;
    hi[3 * i + d] = h + grow;
  }
}

/* Span g of the grid boxes (first .. first + count): their bounds and sum
 * of extents, in box order (7 per span). */
__kernel void snh_broad_bounds(__global const real* lo, __global const real* hi, const int first, const int count,
                               __global real* partial) {
  const int g = get_global_id(0);
  const int begin = g * SNH_BROAD_SPAN;
  if (begin >= count) return;
  const int end = min(begin + SNH_BROAD_SPAN, count);
  real b[6], extent = SNH_R(0);
  for (int d = 0; d < 3; ++d) {
    b[d] = lo[3 * (first + begin) + d];
    b[3 + d] = hi[3 * (first + begin) + d];
  }
  for (int i = begin; i < end; ++i)
    for (int d = 0; d < 3; ++d) {
      const real l = lo[3 * (first + i) + d], h = hi[3 * (first + i) + d];
      b[d] = l < b[d] ? l : b[d];
      b[3 + d] = h > b[3 + d] ? h : b[3 + d];
      extent += h - l;
    }
  for (int k = 0; k < 6; ++k) partial[7 * g + k] = b[k];
  partial[7 * g + 6] = extent;
}

/* One work-item: the grid (origin and cell size into grid, 4; cells per
 * axis into dims, 3) from the spans' bounds, as the host's: the cell the
 * mean box extent, grown by 1.5 until the grid has at most max(64, 8 *
 * count) cells. Positions that are not finite give one cell. */
__kernel void snh_broad_grid(__global const real* partial, const int spans, const int count, __global real* grid,
                             __global int* dims) {
  if (get_global_id(0) != 0) return;
  real b[6], extent = SNH_R(0);
  for (int k = 0; k < 6; ++k) b[k] = partial[k];
  for (int g = 0; g < spans; ++g) {
    for (int d = 0; d < 3; ++d) {
      b[d] = partial[7 * g + d] < b[d] ? partial[7 * g + d] : b[d];
      b[3 + d] = partial[7 * g + 3 + d] > b[3 + d] ? partial[7 * g + 3 + d] : b[3 + d];
    }
    extent += partial[7 * g + 6];
  }
  real span = SNH_R(0);
  int finite = 1;
  for (int d = 0; d < 3; ++d) {
    span = b[3 + d] - b[d] > span ? b[3 + d] - b[d] : span;
    finite = finite && isfinite(b[d]) && isfinite(b[3 + d]);
  }
  real cell = extent / (SNH_R(3) * (real)count);
  if (!(cell > SNH_R(0))) cell = span > SNH_R(0) ? span : SNH_R(1);
  const real cap = (real)max(64, 8 * count);
  for (int guard = 0; finite && guard < 4096; ++guard) {
    real cells = SNH_R(1);
    for (int d = 0; d < 3; ++d) cells *= floor((b[3 + d] - b[d]) / cell) + SNH_R(1);
    if (cells <= cap) break;
    cell *= SNH_R(1.5);
  }
  for (int d = 0; d < 3; ++d) {
    grid[d] = b[d];
    dims[d] = finite ? (int)floor((b[3 + d] - b[d]) / cell) + 1 : 1;
  }
  grid[3] = cell;
}

/* The cell of coordinate c along an axis, clamped to the grid. */
SNH_FN int broad_cell(const real c, const real origin, const real cell, const int dim) {
  const real f = floor((c - origin) / cell);
  if (!(f >= SNH_R(0))) return 0;
  if (f >= (real)(dim - 1)) return dim - 1;
  return (int)f;
}

SNH_FN void broad_cell_range(__global const real* lo, __global const real* hi, const int box, __global const real* grid,
                             __global const int* dims, int* from, int* to) {
  for (int d = 0; d < 3; ++d) {
    from[d] = broad_cell(lo[3 * box + d], grid[d], grid[3], dims[d]);
    to[d] = broad_cell(hi[3 * box + d], grid[d], grid[3], dims[d]);
  }
}

/* Grid box i's count of cells. */
__kernel void snh_broad_cell_counts(__global const real* lo, __global const real* hi, const int first, const int count,
                                    __global const real* grid, __global const int* dims, __global int* counts) {
  const int i = get_global_id(0);
  if (i >= count) return;
  int from[3], to[3];
  broad_cell_range(lo, hi, first + i, grid, dims, from, to);
  counts[i] = (to[0] - from[0] + 1) * (to[1] - from[1] + 1) * (to[2] - from[2] + 1);
}

/* Grid box i's (cell, i) entries from offsets[i]. */
__kernel void snh_broad_cell_entries(__global const real* lo, __global const real* hi, const int first, const int count,
                                     __global const real* grid, __global const int* dims, __global const int* offsets,
                                     __global ulong* keys, __global uint* values) {
  const int i = get_global_id(0);
  if (i >= count) return;
  int from[3], to[3];
  broad_cell_range(lo, hi, first + i, grid, dims, from, to);
  int at = offsets[i];
  for (int z = from[2]; z <= to[2]; ++z)
    for (int y = from[1]; y <= to[1]; ++y)
      for (int x = from[0]; x <= to[0]; ++x) {
        keys[at] = ((ulong)z * (ulong)dims[1] + (ulong)y) * (ulong)dims[0] + (ulong)x;
        values[at] = (uint)i;
        ++at;
      }
}

SNH_FN int broad_excluded(__global const ulong* excluded, const int count, const ulong key) {
  int lo = 0, hi = count;
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (excluded[mid] < key)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < count && excluded[lo] == key;
}

/* Query box a's candidate pairs (a point: point-triangle; an edge:
 * edge-edge with later edges): with `write` 0 their count into counts[a],
 * else their keys from offsets[a], sorted. */
__kernel void snh_broad_query(__global const real* lo, __global const real* hi, __global const int* points,
                              const int point_count, __global const int* edges, const int edge_count,
                              __global const int* triangles, const int triangle_count, __global const real* grid,
                              __global const int* dims, __global const ulong* cell_keys,
                              __global const uint* cell_boxes, const int entries, __global const ulong* excluded,
                              const int excluded_count, const int write, __global int* counts,
                              __global const int* offsets, __global ulong* pairs) {
  const int a = get_global_id(0);
  const int queries = point_count + edge_count;
  if (a >= queries) return;
  const int kind = a < point_count ? 0 : 1;
  const int ia = kind == 0 ? a : a - point_count;
  int va[2];
  if (kind == 0) {
    va[0] = va[1] = points[ia];
  } else {
    va[0] = edges[2 * ia];
    va[1] = edges[2 * ia + 1];
  }
  real alo[3], ahi[3];
  for (int d = 0; d < 3; ++d) {
    alo[d] = lo[3 * a + d];
    ahi[d] = hi[3 * a + d];
  }
  int from[3], to[3];
  broad_cell_range(lo, hi, a, grid, dims, from, to);
  const int begin = write ? offsets[a] : 0;
  int found = 0;
  for (int z = from[2]; z <= to[2]; ++z)
    for (int y = from[1]; y <= to[1]; ++y)
      for (int x = from[0]; x <= to[0]; ++x) {
        const ulong cell = ((ulong)z * (ulong)dims[1] + (ulong)y) * (ulong)dims[0] + (ulong)x;
        int m = 0, hi_m = entries;
        while (m < hi_m) {
          const int mid = m + (hi_m - m) / 2;
          if (cell_keys[mid] < cell)
            m = mid + 1;
          else
            hi_m = mid;
        }
        for (; m < entries && cell_keys[m] == cell; ++m) {
          const int g = (int)cell_boxes[m];
          int b, vb[3];
          if (kind == 0) {
            if (g >= triangle_count) break; /* the cell's triangles come first */
            b = g;
            vb[0] = triangles[3 * b];
            vb[1] = triangles[3 * b + 1];
            vb[2] = triangles[3 * b + 2];
            if (vb[0] == va[0] || vb[1] == va[0] || vb[2] == va[0]) continue;
          } else {
            b = g - triangle_count;
            if (b <= ia) continue;
            vb[0] = edges[2 * b];
            vb[1] = edges[2 * b + 1];
            if (va[0] == vb[0] || va[0] == vb[1] || va[1] == vb[0] || va[1] == vb[1]) continue;
          }
          const int box = queries + g;
          int overlaps = 1, here = 1;
          for (int d = 0; d < 3; ++d) {
            const real blo = lo[3 * box + d], bhi = hi[3 * box + d];
            if (alo[d] > bhi || blo > ahi[d]) overlaps = 0;
            /* Counted in the cell of the intersection's low corner only. */
            const int at = d == 0 ? x : (d == 1 ? y : z);
            if (broad_cell(alo[d] > blo ? alo[d] : blo, grid[d], grid[3], dims[d]) != at) here = 0;
          }
          if (!overlaps || !here) continue;
          const ulong key = broad_pair_key(kind, ia, b);
          if (excluded_count > 0 && broad_excluded(excluded, excluded_count, key)) continue;
          if (write) pairs[begin + found] = key;
          ++found;
        }
      }
  if (!write) {
    counts[a] = found;
    return;
  }
  /* Insertion sort of this query's few pairs. */
  for (int i = 1; i < found; ++i) {
    const ulong key = pairs[begin + i];
    int j = i - 1;
    while (j >= 0 && pairs[begin + j] > key) {
      pairs[begin + j + 1] = pairs[begin + j];
      --j;
    }
    pairs[begin + j + 1] = key;
  }
}

/* Pair i from its key: vertices, kind and the edge-edge mollifier's
 * threshold (mollifier times the rest edges' squared lengths). */
__kernel void snh_broad_pairs(__global const ulong* keys, const int count, __global const int* points,
                              __global const int* edges, __global const int* triangles,
                              __global const real* edge_rest_squared, const real mollifier, __global int4* vertex,
                              __global int* kind, __global real* ex) {
  const int i = get_global_id(0);
  if (i >= count) return;
  const ulong key = keys[i];
  const int k = (int)(key >> 62), a = (int)((key >> 31) & 0x7fffffff), b = (int)(key & 0x7fffffff);
  if (k == 0) {
    vertex[i] = (int4)(points[a], triangles[3 * b], triangles[3 * b + 1], triangles[3 * b + 2]);
    ex[i] = SNH_R(0);
  } else {
    vertex[i] = (int4)(edges[2 * a], edges[2 * a + 1], edges[2 * b], edges[2 * b + 1]);
    ex[i] = mollifier * edge_rest_squared[a] * edge_rest_squared[b];
  }
  kind[i] = k;
}

/* 1 for a pair closer than dhat (squared distance below sh), else 0. */
__kernel void snh_broad_near_flags(__global const real* distance, const int count, const real sh, __global int* flags) {
  const int i = get_global_id(0);
  if (i >= count) return;
  flags[i] = distance[i] < sh ? 1 : 0;
}

/* The flagged pairs, in order, at their scanned offsets. */
__kernel void snh_broad_compact(__global const int* flags, __global const int* offsets, const int count,
                                __global const ulong* keys, __global const int4* vertex, __global const int* kind,
                                __global const real* ex, __global ulong* out_keys, __global int4* out_vertex,
                                __global int* out_kind, __global real* out_ex) {
  const int i = get_global_id(0);
  if (i >= count || !flags[i]) return;
  const int at = offsets[i];
  out_keys[at] = keys[i];
  out_vertex[at] = vertex[i];
  out_kind[at] = kind[i];
  out_ex[at] = ex[i];
}

/* The index lists' sort entries per pair: incidences (surface vertex <<
 * 32, pair * 4 + corner) and blocks (row << 32 | column, pair * 16 + 4 row
 * corner + column corner). */
__kernel void snh_broad_list_entries(__global const int4* vertex, const int count, __global ulong* incidence_keys,
                                     __global uint* incidence_values, __global ulong* block_keys,
                                     __global uint* block_values) {
  const int i = get_global_id(0);
  if (i >= count) return;
  const int4 p = vertex[i];
  const int v[4] = {p.x, p.y, p.z, p.w};
  for (int r = 0; r < 4; ++r) {
    incidence_keys[4 * i + r] = (ulong)v[r] << 32;
    incidence_values[4 * i + r] = (uint)(4 * i + r);
    for (int c = 0; c < 4; ++c) {
      block_keys[16 * i + 4 * r + c] = ((ulong)v[r] << 32) | (ulong)v[c];
      block_values[16 * i + 4 * r + c] = (uint)(16 * i + 4 * r + c);
    }
  }
}

/* 1 where a sorted block entry starts a new (row, column). */
__kernel void snh_broad_block_starts(__global const ulong* keys, const int n, __global int* starts) {
  const int i = get_global_id(0);
  if (i >= n) return;
  starts[i] = i == 0 || keys[i] != keys[i - 1] ? 1 : 0;
}

/* Per block b (starting at sorted entry i, b = its scanned offset): its
 * column and first contribution; the last entry closes the list. */
__kernel void snh_broad_block_lists(__global const ulong* keys, const int n, __global const int* starts,
                                    __global const int* block_of, __global int* columns,
                                    __global int* contribution_offsets) {
  const int i = get_global_id(0);
  if (i >= n) return;
  if (starts[i]) {
    columns[block_of[i]] = (int)(keys[i] & 0xffffffff);
    contribution_offsets[block_of[i]] = i;
  }
  if (i == n - 1) contribution_offsets[block_of[n]] = n;
}

/* Row s's first block: the block of the first entry with row >= s (the
 * entries' lower bounds, snh_sort_lower_bounds). */
__kernel void snh_broad_block_rows(__global const int* entry_bounds, __global const int* block_of, const int count,
                                   __global int* rows) {
  const int s = get_global_id(0);
  if (s > count) return;
  rows[s] = block_of[entry_bounds[s]];
}
