// Barrier self-contact's broad phase on the device (kernels/contact/
// broad_phase.cl, kernels/sort.cl): from the surface positions q (and a
// step dq) already on the device, the candidate pairs, the same set and
// order as BarrierContact::candidate_pairs (the host reference), the pairs
// closer than dhat among them, and the index lists the pair sums run
// through. Integer sorts and scans only, no atomics: the lists are the
// same on every run and every device. What crosses to the host: one int
// per count that sizes a buffer (cell entries and candidates per broad
// phase, pairs within dhat per filter, blocks per list). Internal to the
// library.
#pragma once

#include <vector>

#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "solver/contact/barrier_contact.h"

namespace snh::solver {

// A pair list on the device, sorted by key (kind << 62 | a << 31 | b, a and
// b the pair's point, triangle or edge indices, as BarrierContact's
// exclusion keys): per pair its key, vertices (int4, surface vertex
// indices), kind and edge-edge mollifier threshold (the pair math's real).
struct DevicePairList {
  device::Buffer keys, vertex, kind, ex;
  int count = 0, capacity = 0;
};

// The index lists of a pair list (kernels/contact/barrier_pairs.cl's sums):
// per surface vertex its incidences (pair * 4 + corner) in pair order; the
// pairs' 3x3 blocks per surface vertex pair (block CSR: rows, columns
// ascending) and per block its contributions (pair * 16 + 4 row corner +
// column corner) in pair order.
struct DevicePairLists {
  device::Buffer incidence_offsets, incidence, rows, columns, contribution_offsets, contributions;
  int blocks = 0;
};

class BarrierBroadPhase {
 public:
  // `real_bytes`: the pair math's real (8 with fp64, else 4).
  BarrierBroadPhase(device::OpenClContext& cl, size_t real_bytes, PhaseProfiler* profiler);

  // The surface's points, edges, triangles, rest edges and the pairs it
  // leaves out (BarrierContact::exclusion_keys), uploaded.
  void set_surface(const BarrierContact& contact);
  // The candidate pairs at q (dq null) or along q + t dq, t in [0, 1]:
  // boxes inflated by `inflate` overlapping, no shared vertex, not left out.
  void candidates(cl_mem q, cl_mem dq, double inflate, DevicePairList& out);
  // The candidates whose squared distance (per candidate, `distance`) is
  // below sh, in order.
  void near(const DevicePairList& candidates, cl_mem distance, double sh, DevicePairList& out);
  // The index lists of `pairs` over `surface_count` surface vertices.
  void lists(const DevicePairList& pairs, int surface_count, DevicePairLists& out);
  // How many of the first n ints of `flags` are not 0 (one int read).
  int count_set(cl_mem flags, int n) { return scan(flags, n, offsets_); }
  // `pairs` (found on the host, in their order) as a device list.
  void upload(const std::vector<BarrierPair>& pairs, DevicePairList& out);
  // The list read back (tests and inspection).
  std::vector<BarrierPair> download(const DevicePairList& pairs);

 private:
  // offsets[0 .. n] = the exclusive prefix sums of counts[0 .. n - 1] and
  // their total; returns the total (one int read).
  int scan(cl_mem counts, int n, device::Buffer& offsets);
  // Sorts the first n (key, value) entries, by key then value; the buffers
  // hold at least the next power of two (padded here).
  void sort(cl_mem keys, cl_mem values, int n);
  // A buffer of at least `bytes`, grown (never shrunk) when smaller.
  void reserve(device::Buffer& buffer, size_t bytes);
  void reserve(DevicePairList& list, int count);

  device::OpenClContext& cl_;
  size_t real_bytes_;
  PhaseProfiler* profiler_;
  int point_count_ = 0, edge_count_ = 0, triangle_count_ = 0, excluded_count_ = 0;
  device::Buffer points_, edges_, triangles_, edge_rest_squared_, excluded_;
  // Scratch, grown as needed.
  device::Buffer lo_, hi_, partial_, grid_, dims_, counts_, offsets_, span_sums_, total_, cell_keys_, cell_boxes_,
      incidence_keys_, block_keys_, starts_, block_of_, entry_bounds_;
  device::Kernel boxes_k_, bounds_k_, grid_k_, cell_counts_k_, cell_entries_k_, query_k_, pairs_k_, flags_k_,
      compact_k_, list_entries_k_, block_starts_k_, block_lists_k_, block_rows_k_, bitonic_k_, bitonic_block_k_, pad_k_,
      scan_spans_k_, scan_span_offsets_k_, scan_offsets_k_, lower_bounds_k_;
};

}  // namespace snh::solver
