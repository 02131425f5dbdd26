// Point caches: PC2 (little-endian) and MDD (big-endian) (snh/character.h,
// docs/formats.md).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "snh/character.h"
#include "snh/error.h"

namespace snh {
namespace {

constexpr char kPc2Magic[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};

// 4 bytes of a value in the chosen byte order, whatever the host's.
template <class T>
void put(std::string& out, T value, bool big_endian) {
  static_assert(sizeof(T) == 4, "4-byte fields only");
  uint32_t u;
  std::memcpy(&u, &value, 4);
  for (int i = 0; i < 4; ++i) {
    const int shift = big_endian ? 8 * (3 - i) : 8 * i;
    out.push_back(static_cast<char>((u >> shift) & 0xffu));
  }
}

template <class T>
T get(const std::string& in, size_t& at, bool big_endian, const std::string& path, const char* what) {
  if (at + 4 > in.size())
    throw Error(path + ": the file ends at byte " + std::to_string(in.size()) + " inside " + what + " (byte " +
                std::to_string(at) + ")");
  uint32_t u = 0;
  for (int i = 0; i < 4; ++i) {
    const uint32_t b = static_cast<unsigned char>(in[at + i]);
    u |= b << (big_endian ? 8 * (3 - i) : 8 * i);
  }
  at += 4;
  T value;
  std::memcpy(&value, &u, 4);
  return value;
}

void check(const std::string& path, const PointCache& cache) {
  for (size_t s = 0; s < cache.samples.size(); ++s)
    if (cache.samples[s].size() != 3 * cache.point_count)
      throw Error(path + ": sample " + std::to_string(s) + " has " + std::to_string(cache.samples[s].size()) +
                  " coordinates for " + std::to_string(cache.point_count) + " points");
  if (cache.point_count > 0x7fffffffu || cache.samples.size() > 0x7fffffffu)
    throw Error(path + ": too many points or samples for a 32-bit count");
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw Error(path + ": cannot write the point cache");
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the point cache");
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void read_points(const std::string& in, size_t& at, bool big_endian, const std::string& path, PointCache& cache,
                 size_t samples) {
  if ((in.size() - at) / 12 / std::max<size_t>(cache.point_count, 1) < samples && cache.point_count > 0)
    throw Error(path + ": " + std::to_string(samples) + " samples of " + std::to_string(cache.point_count) +
                " points need " + std::to_string(12 * samples * cache.point_count) +
                " bytes after the header, the file has " + std::to_string(in.size() - at));
  cache.samples.assign(samples, std::vector<float>(3 * cache.point_count));
  for (auto& sample : cache.samples)
    for (float& v : sample) v = get<float>(in, at, big_endian, path, "the points");
  if (at != in.size()) throw Error(path + ": " + std::to_string(in.size() - at) + " bytes after the last sample");
}

}  // namespace

void write_pc2(const std::string& path, const PointCache& cache) {
  check(path, cache);
  std::string b(kPc2Magic, kPc2Magic + 12);
  put<int32_t>(b, 1, false);
  put<int32_t>(b, static_cast<int32_t>(cache.point_count), false);
  put<float>(b, static_cast<float>(cache.start_frame), false);
  put<float>(b, static_cast<float>(cache.sample_rate), false);
  put<int32_t>(b, static_cast<int32_t>(cache.samples.size()), false);
  for (const auto& sample : cache.samples)
    for (float v : sample) put<float>(b, v, false);
  write_bytes(path, b);
}

void write_mdd(const std::string& path, const PointCache& cache) {
  check(path, cache);
  if (cache.times.size() != cache.samples.size())
    throw Error(path + ": " + std::to_string(cache.times.size()) + " times for " +
                std::to_string(cache.samples.size()) + " frames");
  std::string b;
  put<int32_t>(b, static_cast<int32_t>(cache.samples.size()), true);
  put<int32_t>(b, static_cast<int32_t>(cache.point_count), true);
  for (double t : cache.times) put<float>(b, static_cast<float>(t), true);
  for (const auto& sample : cache.samples)
    for (float v : sample) put<float>(b, v, true);
  write_bytes(path, b);
}

PointCache read_pc2(const std::string& path) {
  const std::string in = read_bytes(path);
  if (in.size() < 32 || std::memcmp(in.data(), kPc2Magic, 12) != 0)
    throw Error(path + ": not a PC2 file (no \"POINTCACHE2\\0\" header of 32 bytes)");
  size_t at = 12;
  const int32_t version = get<int32_t>(in, at, false, path, "the header");
  if (version != 1) throw Error(path + ": PC2 version " + std::to_string(version) + ", expected 1");
  const int32_t points = get<int32_t>(in, at, false, path, "the header");
  PointCache cache;
  cache.start_frame = get<float>(in, at, false, path, "the header");
  cache.sample_rate = get<float>(in, at, false, path, "the header");
  const int32_t samples = get<int32_t>(in, at, false, path, "the header");
  if (points < 0 || samples < 0) throw Error(path + ": negative point or sample count");
  cache.point_count = static_cast<size_t>(points);
  read_points(in, at, false, path, cache, static_cast<size_t>(samples));
  for (size_t s = 0; s < cache.samples.size(); ++s)
    cache.times.push_back(cache.start_frame + cache.sample_rate * static_cast<double>(s));
  return cache;
}

PointCache read_mdd(const std::string& path) {
  const std::string in = read_bytes(path);
  size_t at = 0;
  const int32_t frames = get<int32_t>(in, at, true, path, "the header");
  const int32_t points = get<int32_t>(in, at, true, path, "the header");
  if (frames < 0 || points < 0) throw Error(path + ": negative frame or point count");
  if ((in.size() - at) / 4 < static_cast<size_t>(frames)) throw Error(path + ": the file ends inside the frame times");
  PointCache cache;
  cache.point_count = static_cast<size_t>(points);
  for (int32_t f = 0; f < frames; ++f) cache.times.push_back(get<float>(in, at, true, path, "the frame times"));
  read_points(in, at, true, path, cache, static_cast<size_t>(frames));
  return cache;
}

void write_point_cache(const std::string& path, const PointCache& cache) {
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".pc2")
    write_pc2(path, cache);
  else if (ext == ".mdd")
    write_mdd(path, cache);
  else
    throw Error(path + ": a point cache ends in .pc2 or .mdd");
}

CharacterCacheSeries::CharacterCacheSeries(const Character& character, std::string pc2, std::string mdd,
                                           std::string lbs)
    : character_(&character), pc2_(std::move(pc2)), mdd_(std::move(mdd)), lbs_(std::move(lbs)) {
  if (!character.has_clip) throw Error(character.file + ": point caches need an animation clip");
  for (PointCache* c : {&simulated_, &skinned_}) {
    c->point_count = character.surface.vertex_count();
    c->start_frame = character.clip.first_frame;
    c->sample_rate = 1.0;
  }
}

void CharacterCacheSeries::add(int clip_frame, const Points& surface) {
  const Character& c = *character_;
  const int frame = clip_frame - c.clip.first_frame;
  if (frame < 0 || static_cast<size_t>(frame) >= c.clip.frame_count())
    throw Error(c.file + ": point cache: frame " + std::to_string(clip_frame) + " is not among the sampled frames " +
                std::to_string(c.clip.first_frame) + ".." +
                std::to_string(c.clip.first_frame + static_cast<int>(c.clip.frame_count()) - 1));
  if (surface.size() != c.surface.vertex_count())
    throw Error(c.file + ": point cache: " + std::to_string(surface.size()) + " positions for " +
                std::to_string(c.surface.vertex_count()) + " vertices");
  simulated_.samples.emplace_back(surface.xyz().begin(), surface.xyz().end());
  simulated_.times.push_back(c.clip.times[frame]);
  if (!lbs_.empty()) {
    const Points s = linear_blend_skinning(c.surface.positions, c.weights, c.clip.skinning[frame]);
    skinned_.samples.emplace_back(s.xyz().begin(), s.xyz().end());
    skinned_.times.push_back(c.clip.times[frame]);
  }
}

void CharacterCacheSeries::finish() {
  if (!pc2_.empty()) write_pc2(pc2_, simulated_);
  if (!mdd_.empty()) write_mdd(mdd_, simulated_);
  if (!lbs_.empty()) write_point_cache(lbs_, skinned_);
}

}  // namespace snh
