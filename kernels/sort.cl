/* Integer sort and scan on the device, deterministic on every device: no
 * floating point, no atomics, every result a function of the input alone.
 *
 * The sort is Batcher's bitonic network over (key, value) entries, ordered
 * by key, then by value, so entries with equal keys come out in one order
 * whatever the device (the network is not stable; the value breaks ties).
 * The host pads the list to a power of two with the largest entry
 * (all bits set) and runs the stages (k, j), k = 2, 4, ..., n and j = k /
 * 2, ..., 1: those within blocks of entries by snh_sort_bitonic_block, a
 * launch per k, the others by snh_sort_bitonic_step, a launch each.
 *
 * The scan is the exclusive prefix sum of int counts in three passes: per
 * span of SNH_SCAN_SPAN entries its sum, one work-item over the spans (and
 * the total, written after the last offset), then per span its entries. */

#define SNH_SCAN_SPAN 256

/* Entries i < l: swapped where the stage's direction (ascending where i &
 * k is 0) wants them the other way round. */
static inline void sort_compare_swap(__global ulong* keys, __global uint* values, const int i, const int l,
                                     const int k) {
  const ulong ki = keys[i], kl = keys[l];
  const uint vi = values[i], vl = values[l];
  const int i_after_l = ki > kl || (ki == kl && vi > vl);
  const int l_after_i = kl > ki || (kl == ki && vl > vi);
  const int ascending = (i & k) == 0;
  if (ascending ? i_after_l : l_after_i) {
    keys[i] = kl;
    keys[l] = ki;
    values[i] = vl;
    values[l] = vi;
  }
}

/* One stage (k, j) over n entries, one work-item per entry. */
__kernel void snh_sort_bitonic_step(__global ulong* keys, __global uint* values, const int j, const int k,
                                    const int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const int l = i ^ j;
  if (l > i) sort_compare_swap(keys, values, i, l, k);
}

/* The stages whose partners lie within one block of `block` entries, one
 * work-item per block, in order: for k = k_first, 2 k_first, ..., k_last,
 * the stages j = min(k, block) / 2, ..., 1. The same network as the steps,
 * in a few launches rather than one per stage. */
__kernel void snh_sort_bitonic_block(__global ulong* keys, __global uint* values, const int k_first, const int k_last,
                                     const int block, const int n) {
  const int begin = get_global_id(0) * block;
  if (begin >= n) return;
  const int end = min(begin + block, n);
  for (int k = k_first; k <= k_last; k *= 2)
    for (int j = min(k, block) / 2; j > 0; j /= 2)
      for (int i = begin; i < end; ++i) {
        const int l = i ^ j;
        if (l > i) sort_compare_swap(keys, values, i, l, k);
      }
}

/* Entries from .. to - 1 set to the largest entry (the padding). */
__kernel void snh_sort_pad(__global ulong* keys, __global uint* values, const int from, const int to) {
  const int i = from + get_global_id(0);
  if (i >= to) return;
  keys[i] = ~(ulong)0;
  values[i] = ~(uint)0;
}

/* Span g's sum of counts. */
__kernel void snh_scan_spans(__global const int* counts, const int n, __global int* span_sums) {
  const int g = get_global_id(0);
  const int begin = g * SNH_SCAN_SPAN;
  if (begin >= n) return;
  const int end = min(begin + SNH_SCAN_SPAN, n);
  int sum = 0;
  for (int i = begin; i < end; ++i) sum += counts[i];
  span_sums[g] = sum;
}

/* One work-item: the spans' sums become their exclusive offsets, in place;
 * offsets[n] and total[0] get the total. */
__kernel void snh_scan_span_offsets(__global int* span_sums, const int spans, const int n, __global int* offsets,
                                    __global int* total) {
  if (get_global_id(0) != 0) return;
  int sum = 0;
  for (int g = 0; g < spans; ++g) {
    const int s = span_sums[g];
    span_sums[g] = sum;
    sum += s;
  }
  offsets[n] = sum;
  total[0] = sum;
}

/* offsets[i] = the sum of counts before i. */
__kernel void snh_scan_offsets(__global const int* counts, const int n, __global const int* span_sums,
                               __global int* offsets) {
  const int g = get_global_id(0);
  const int begin = g * SNH_SCAN_SPAN;
  if (begin >= n) return;
  const int end = min(begin + SNH_SCAN_SPAN, n);
  int sum = span_sums[g];
  for (int i = begin; i < end; ++i) {
    offsets[i] = sum;
    sum += counts[i];
  }
}

/* Per s in [0, count]: the first entry of the sorted keys (n of them) whose
 * key is >= s << shift (n when none): the offsets of a CSR whose rows are
 * the keys' high bits. */
__kernel void snh_sort_lower_bounds(__global const ulong* keys, const int n, const int shift, const int count,
                                    __global int* bounds) {
  const int s = get_global_id(0);
  if (s > count) return;
  const ulong target = ((ulong)s) << shift;
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (keys[mid] < target)
      lo = mid + 1;
    else
      hi = mid;
  }
  bounds[s] = lo;
}
