#include "solver/contact/barrier_broad_phase.h"

#include <algorithm>
#include <climits>
#include <string>

#include "device/kernel_args.h"
#include "snh/error.h"

namespace snh::solver {

namespace {

// Entries per span of the device's scans and bounds (SNH_SCAN_SPAN,
// SNH_BROAD_SPAN).
constexpr int kSpan = 256;

int spans(int count) { return (count + kSpan - 1) / kSpan; }

// Entries per block of the sort's within-block stages (a power of two).
constexpr int kSortBlock = 256;

int power_of_two_at_least(int n) {
  int p = 1;
  while (p < n) p *= 2;
  return p;
}

// A count that sizes a buffer: refused when it does not fit an int (the
// scan's sum wrapped) or the pair keys' 31-bit indices.
int checked_count(int total, const char* what) {
  if (total < 0 || total > (INT_MAX >> 4))
    throw Error(std::string("barrier contact: the device broad phase's ") + what + " overflow");
  return total;
}

}  // namespace

BarrierBroadPhase::BarrierBroadPhase(device::OpenClContext& cl, size_t real_bytes, PhaseProfiler* profiler)
    : cl_(cl), real_bytes_(real_bytes), profiler_(profiler) {
  const device::KernelConfig config;
  const char* broad = "contact/broad_phase.cl";
  boxes_k_ = cl_.kernel(broad, config, "snh_broad_boxes");
  bounds_k_ = cl_.kernel(broad, config, "snh_broad_bounds");
  grid_k_ = cl_.kernel(broad, config, "snh_broad_grid");
  cell_counts_k_ = cl_.kernel(broad, config, "snh_broad_cell_counts");
  cell_entries_k_ = cl_.kernel(broad, config, "snh_broad_cell_entries");
  query_k_ = cl_.kernel(broad, config, "snh_broad_query");
  pairs_k_ = cl_.kernel(broad, config, "snh_broad_pairs");
  flags_k_ = cl_.kernel(broad, config, "snh_broad_near_flags");
  compact_k_ = cl_.kernel(broad, config, "snh_broad_compact");
  list_entries_k_ = cl_.kernel(broad, config, "snh_broad_list_entries");
  block_starts_k_ = cl_.kernel(broad, config, "snh_broad_block_starts");
  block_lists_k_ = cl_.kernel(broad, config, "snh_broad_block_lists");
  block_rows_k_ = cl_.kernel(broad, config, "snh_broad_block_rows");
  const char* sorting = "sort.cl";
  bitonic_k_ = cl_.kernel(sorting, config, "snh_sort_bitonic_step");
  bitonic_block_k_ = cl_.kernel(sorting, config, "snh_sort_bitonic_block");
  pad_k_ = cl_.kernel(sorting, config, "snh_sort_pad");
  scan_spans_k_ = cl_.kernel(sorting, config, "snh_scan_spans");
  scan_span_offsets_k_ = cl_.kernel(sorting, config, "snh_scan_span_offsets");
  scan_offsets_k_ = cl_.kernel(sorting, config, "snh_scan_offsets");
  lower_bounds_k_ = cl_.kernel(sorting, config, "snh_sort_lower_bounds");
  total_ = cl_.buffer(CL_MEM_READ_WRITE, sizeof(int));
  grid_ = cl_.buffer(CL_MEM_READ_WRITE, 4 * real_bytes_);
  dims_ = cl_.buffer(CL_MEM_READ_WRITE, 3 * sizeof(int));
}

void BarrierBroadPhase::reserve(device::Buffer& buffer, size_t bytes) {
  bytes = std::max<size_t>(bytes, 1);
  if (buffer && device::OpenClContext::bytes(buffer.get()) >= bytes) return;
  buffer = cl_.buffer(CL_MEM_READ_WRITE, bytes + bytes / 2);  // room to grow
}

void BarrierBroadPhase::reserve(DevicePairList& list, int count) {
  if (list.keys && list.capacity >= count) return;
  const int capacity = std::max(1, count + count / 2);
  list.keys = cl_.buffer(CL_MEM_READ_WRITE, capacity * sizeof(cl_ulong));
  list.vertex = cl_.buffer(CL_MEM_READ_WRITE, capacity * sizeof(cl_int4));
  list.kind = cl_.buffer(CL_MEM_READ_WRITE, capacity * sizeof(int));
  list.ex = cl_.buffer(CL_MEM_READ_WRITE, capacity * real_bytes_);
  list.capacity = capacity;
}

void BarrierBroadPhase::set_surface(const BarrierContact& contact) {
  point_count_ = static_cast<int>(contact.point_count());
  edge_count_ = static_cast<int>(contact.edge_count());
  triangle_count_ = static_cast<int>(contact.triangle_count());
  excluded_count_ = static_cast<int>(contact.exclusion_keys().size());
  auto ints = [&](const std::vector<int>& values) {
    return cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(values.size(), 1) * sizeof(int), values.data());
  };
  PhaseScope transfer(profiler_, Phase::transfers);
  points_ = ints(contact.points());
  edges_ = ints(contact.edges());
  triangles_ = ints(contact.triangles());
  const std::vector<double>& rest = contact.edge_rest_squared();
  if (real_bytes_ == sizeof(double)) {
    edge_rest_squared_ = cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(rest.size(), 1) * sizeof(double), rest.data());
  } else {
    const std::vector<float> narrow(rest.begin(), rest.end());
    edge_rest_squared_ =
        cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(narrow.size(), 1) * sizeof(float), narrow.data());
  }
  const std::vector<uint64_t>& keys = contact.exclusion_keys();
  const std::vector<cl_ulong> excluded(keys.begin(), keys.end());
  excluded_ = cl_.buffer(CL_MEM_READ_ONLY, std::max<size_t>(excluded.size(), 1) * sizeof(cl_ulong), excluded.data());
}

int BarrierBroadPhase::scan(cl_mem counts, int n, device::Buffer& offsets) {
  const int groups = std::max(1, spans(n));
  reserve(offsets, (static_cast<size_t>(n) + 1) * sizeof(int));
  reserve(span_sums_, static_cast<size_t>(groups) * sizeof(int));
  device::KernelArgs sums(scan_spans_k_.get());
  sums.add(counts).add(n).add(span_sums_.get());
  cl_.run(sums.bind(), static_cast<size_t>(groups));
  device::KernelArgs between(scan_span_offsets_k_.get());
  between.add(span_sums_.get()).add(n > 0 ? groups : 0).add(n).add(offsets.get()).add(total_.get());
  cl_.run(between.bind(), 1);
  device::KernelArgs within(scan_offsets_k_.get());
  within.add(counts).add(n).add(span_sums_.get()).add(offsets.get());
  cl_.run(within.bind(), static_cast<size_t>(groups));
  int total = 0;
  PhaseScope transfer(profiler_, Phase::transfers);
  cl_.read(total_.get(), sizeof total, &total);
  return total;
}

void BarrierBroadPhase::sort(cl_mem keys, cl_mem values, int n) {
  const int size = power_of_two_at_least(n);
  if (size > n) {
    device::KernelArgs pad(pad_k_.get());
    pad.add(keys).add(values).add(n).add(size);
    cl_.run(pad.bind(), static_cast<size_t>(size - n));
  }
  // The stages within blocks of kSortBlock entries in one launch per k.
  const int block = std::min(kSortBlock, size);
  auto within_blocks = [&](int k_first, int k_last) {
    device::KernelArgs args(bitonic_block_k_.get());
    args.add(keys).add(values).add(k_first).add(k_last).add(block).add(size);
    cl_.run(args.bind(), static_cast<size_t>(size / block));
  };
  within_blocks(2, block);
  for (int k = 2 * block; k <= size; k *= 2) {
    for (int j = k / 2; j >= block; j /= 2) {
      device::KernelArgs step(bitonic_k_.get());
      step.add(keys).add(values).add(j).add(k).add(size);
      cl_.run(step.bind(), static_cast<size_t>(size));
    }
    within_blocks(k, k);
  }
}

void BarrierBroadPhase::candidates(cl_mem q, cl_mem dq, double inflate, DevicePairList& out) {
  out.count = 0;
  const int queries = point_count_ + edge_count_, boxes = triangle_count_ + edge_count_;
  if (queries == 0 || boxes == 0) return;
  auto add_real = [&](device::KernelArgs& args, double value) {
    if (real_bytes_ == sizeof(double))
      args.add(value);
    else
      args.add(static_cast<float>(value));
  };
  const size_t all = static_cast<size_t>(queries) + static_cast<size_t>(boxes);
  reserve(lo_, 3 * all * real_bytes_);
  reserve(hi_, 3 * all * real_bytes_);
  {
    device::KernelArgs args(boxes_k_.get());
    args.add(q).add(dq ? dq : q).add(dq ? 1 : 0).add(points_.get()).add(point_count_).add(edges_.get());
    args.add(edge_count_).add(triangles_.get()).add(triangle_count_);
    add_real(args, inflate);
    args.add(lo_.get()).add(hi_.get());
    cl_.run(args.bind(), all);
  }
  // The grid over the grid boxes, and their (cell, box) entries, sorted.
  const int groups = spans(boxes);
  reserve(partial_, 7 * static_cast<size_t>(groups) * real_bytes_);
  {
    device::KernelArgs bounds(bounds_k_.get());
    bounds.add(lo_.get()).add(hi_.get()).add(queries).add(boxes).add(partial_.get());
    cl_.run(bounds.bind(), static_cast<size_t>(groups));
    device::KernelArgs grid(grid_k_.get());
    grid.add(partial_.get()).add(groups).add(boxes).add(grid_.get()).add(dims_.get());
    cl_.run(grid.bind(), 1);
  }
  reserve(counts_, static_cast<size_t>(std::max(boxes, queries)) * sizeof(int));
  {
    device::KernelArgs counts(cell_counts_k_.get());
    counts.add(lo_.get()).add(hi_.get()).add(queries).add(boxes).add(grid_.get()).add(dims_.get());
    counts.add(counts_.get());
    cl_.run(counts.bind(), static_cast<size_t>(boxes));
  }
  const int entries = checked_count(scan(counts_.get(), boxes, offsets_), "grid cells");
  const size_t padded = static_cast<size_t>(power_of_two_at_least(entries));
  reserve(cell_keys_, padded * sizeof(cl_ulong));
  reserve(cell_boxes_, padded * sizeof(cl_uint));
  {
    device::KernelArgs fill(cell_entries_k_.get());
    fill.add(lo_.get()).add(hi_.get()).add(queries).add(boxes).add(grid_.get()).add(dims_.get());
    fill.add(offsets_.get()).add(cell_keys_.get()).add(cell_boxes_.get());
    cl_.run(fill.bind(), static_cast<size_t>(boxes));
  }
  sort(cell_keys_.get(), cell_boxes_.get(), entries);
  // Per query box its pairs: counted, scanned, written and sorted.
  auto query = [&](int write, cl_mem pairs) {
    device::KernelArgs args(query_k_.get());
    args.add(lo_.get()).add(hi_.get()).add(points_.get()).add(point_count_).add(edges_.get()).add(edge_count_);
    args.add(triangles_.get()).add(triangle_count_).add(grid_.get()).add(dims_.get()).add(cell_keys_.get());
    args.add(cell_boxes_.get()).add(entries).add(excluded_.get()).add(excluded_count_).add(write);
    args.add(counts_.get()).add(offsets_.get()).add(pairs);
    cl_.run(args.bind(), static_cast<size_t>(queries));
  };
  query(0, counts_.get());
  const int count = checked_count(scan(counts_.get(), queries, offsets_), "candidate pairs");
  if (count == 0) return;
  reserve(out, count);
  query(1, out.keys.get());
  device::KernelArgs pairs(pairs_k_.get());
  pairs.add(out.keys.get()).add(count).add(points_.get()).add(edges_.get()).add(triangles_.get());
  pairs.add(edge_rest_squared_.get());
  add_real(pairs, kMollifierFactor);
  pairs.add(out.vertex.get()).add(out.kind.get()).add(out.ex.get());
  cl_.run(pairs.bind(), static_cast<size_t>(count));
  out.count = count;
}

void BarrierBroadPhase::near(const DevicePairList& candidates, cl_mem distance, double sh, DevicePairList& out) {
  out.count = 0;
  const int n = candidates.count;
  if (n == 0) return;
  reserve(counts_, static_cast<size_t>(n) * sizeof(int));
  device::KernelArgs flags(flags_k_.get());
  flags.add(distance).add(n);
  if (real_bytes_ == sizeof(double))
    flags.add(sh);
  else
    flags.add(static_cast<float>(sh));
  flags.add(counts_.get());
  cl_.run(flags.bind(), static_cast<size_t>(n));
  const int count = scan(counts_.get(), n, offsets_);
  if (count == 0) return;
  reserve(out, count);
  device::KernelArgs compact(compact_k_.get());
  compact.add(counts_.get()).add(offsets_.get()).add(n).add(candidates.keys.get()).add(candidates.vertex.get());
  compact.add(candidates.kind.get()).add(candidates.ex.get()).add(out.keys.get()).add(out.vertex.get());
  compact.add(out.kind.get()).add(out.ex.get());
  cl_.run(compact.bind(), static_cast<size_t>(n));
  out.count = count;
}

void BarrierBroadPhase::lists(const DevicePairList& pairs, int surface_count, DevicePairLists& out) {
  const int count = pairs.count;
  out.blocks = 0;
  if (count == 0) return;
  const int incidences = 4 * count, contributions = 16 * count;
  reserve(incidence_keys_, static_cast<size_t>(power_of_two_at_least(incidences)) * sizeof(cl_ulong));
  reserve(out.incidence, static_cast<size_t>(power_of_two_at_least(incidences)) * sizeof(cl_uint));
  reserve(block_keys_, static_cast<size_t>(power_of_two_at_least(contributions)) * sizeof(cl_ulong));
  reserve(out.contributions, static_cast<size_t>(power_of_two_at_least(contributions)) * sizeof(cl_uint));
  device::KernelArgs entries(list_entries_k_.get());
  entries.add(pairs.vertex.get()).add(count).add(incidence_keys_.get()).add(out.incidence.get());
  entries.add(block_keys_.get()).add(out.contributions.get());
  cl_.run(entries.bind(), static_cast<size_t>(count));
  // Incidences by surface vertex, then pair order.
  sort(incidence_keys_.get(), out.incidence.get(), incidences);
  reserve(out.incidence_offsets, (static_cast<size_t>(surface_count) + 1) * sizeof(int));
  auto lower_bounds = [&](cl_mem keys, int n, cl_mem bounds) {
    device::KernelArgs args(lower_bounds_k_.get());
    args.add(keys).add(n).add(32).add(surface_count).add(bounds);
    cl_.run(args.bind(), static_cast<size_t>(surface_count) + 1);
  };
  lower_bounds(incidence_keys_.get(), incidences, out.incidence_offsets.get());
  // Blocks by (row, column), contributions in pair order.
  sort(block_keys_.get(), out.contributions.get(), contributions);
  reserve(starts_, static_cast<size_t>(contributions) * sizeof(int));
  device::KernelArgs starts(block_starts_k_.get());
  starts.add(block_keys_.get()).add(contributions).add(starts_.get());
  cl_.run(starts.bind(), static_cast<size_t>(contributions));
  const int blocks = scan(starts_.get(), contributions, block_of_);
  reserve(out.columns, static_cast<size_t>(blocks) * sizeof(int));
  reserve(out.contribution_offsets, (static_cast<size_t>(blocks) + 1) * sizeof(int));
  device::KernelArgs lists(block_lists_k_.get());
  lists.add(block_keys_.get()).add(contributions).add(starts_.get()).add(block_of_.get()).add(out.columns.get());
  lists.add(out.contribution_offsets.get());
  cl_.run(lists.bind(), static_cast<size_t>(contributions));
  reserve(entry_bounds_, (static_cast<size_t>(surface_count) + 1) * sizeof(int));
  lower_bounds(block_keys_.get(), contributions, entry_bounds_.get());
  reserve(out.rows, (static_cast<size_t>(surface_count) + 1) * sizeof(int));
  device::KernelArgs rows(block_rows_k_.get());
  rows.add(entry_bounds_.get()).add(block_of_.get()).add(surface_count).add(out.rows.get());
  cl_.run(rows.bind(), static_cast<size_t>(surface_count) + 1);
  out.blocks = blocks;
}

void BarrierBroadPhase::upload(const std::vector<BarrierPair>& pairs, DevicePairList& out) {
  out.count = 0;
  const size_t n = pairs.size();
  if (n == 0) return;
  reserve(out, static_cast<int>(n));
  std::vector<cl_ulong> keys(n);
  std::vector<cl_int4> vertex(n);
  std::vector<int> kind(n);
  std::vector<double> ex(n);
  for (size_t i = 0; i < n; ++i) {
    keys[i] = i;  // the order they come in
    for (int k = 0; k < 4; ++k) vertex[i].s[k] = pairs[i].vertex[k];
    kind[i] = pairs[i].kind;
    ex[i] = pairs[i].ex;
  }
  PhaseScope transfer(profiler_, Phase::transfers);
  cl_.write(out.keys.get(), n * sizeof(cl_ulong), keys.data());
  cl_.write(out.vertex.get(), n * sizeof(cl_int4), vertex.data());
  cl_.write(out.kind.get(), n * sizeof(int), kind.data());
  if (real_bytes_ == sizeof(double)) {
    cl_.write(out.ex.get(), n * sizeof(double), ex.data());
  } else {
    const std::vector<float> narrow(ex.begin(), ex.end());
    cl_.write(out.ex.get(), n * sizeof(float), narrow.data());
  }
  out.count = static_cast<int>(n);
}

std::vector<BarrierPair> BarrierBroadPhase::download(const DevicePairList& pairs) {
  const size_t n = static_cast<size_t>(pairs.count);
  std::vector<BarrierPair> out(n);
  if (n == 0) return out;
  std::vector<cl_int4> vertex(n);
  std::vector<int> kind(n);
  std::vector<double> ex(n);
  PhaseScope transfer(profiler_, Phase::transfers);
  cl_.read(pairs.vertex.get(), n * sizeof(cl_int4), vertex.data());
  cl_.read(pairs.kind.get(), n * sizeof(int), kind.data());
  if (real_bytes_ == sizeof(double)) {
    cl_.read(pairs.ex.get(), n * sizeof(double), ex.data());
  } else {
    std::vector<float> narrow(n);
    cl_.read(pairs.ex.get(), n * sizeof(float), narrow.data());
    ex.assign(narrow.begin(), narrow.end());
  }
  for (size_t i = 0; i < n; ++i) {
    out[i].kind = kind[i];
    for (int k = 0; k < 4; ++k) out[i].vertex[k] = vertex[i].s[k];
    out[i].ex = ex[i];
  }
  return out;
}

}  // namespace snh::solver
