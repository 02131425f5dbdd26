// The checkpoint file (snh/checkpoint.h): items written and read in one
// order, each read named in the error it may raise.
#include "snh/checkpoint.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "fem/matrix_order.h"
#include "snh/error.h"

namespace snh {

namespace {

constexpr char kMagic[8] = {'S', 'N', 'H', 'S', 'T', 'A', 'T', 'E'};
constexpr uint32_t kVersion = 1;
constexpr uint32_t kByteOrder = 0x01020304u;

class Writer {
 public:
  explicit Writer(const std::string& path) : path_(path), file_(path, std::ios::binary | std::ios::trunc) {
    if (!file_) throw Error("write_checkpoint " + path_ + ": the file cannot be opened for writing");
  }
  void bytes(const void* data, size_t n) {
    file_.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
  }
  void u32(uint32_t v) { bytes(&v, sizeof v); }
  void u64(uint64_t v) { bytes(&v, sizeof v); }
  void f64(double v) { bytes(&v, sizeof v); }
  void flag(bool v) {
    const uint8_t b = v ? 1 : 0;
    bytes(&b, 1);
  }
  void text(const std::string& s) {
    u64(s.size());
    bytes(s.data(), s.size());
  }
  void values(const std::vector<double>& v) {
    u64(v.size());
    bytes(v.data(), v.size() * sizeof(double));
  }
  void points(const Points& p) { values(p.xyz()); }
  template <size_t N>
  void fixed(const std::array<double, N>& a) {
    for (double v : a) f64(v);
  }
  // The rotation goes to the file column-major, as version 1 has always
  // stored it, while RigidTransform holds it row-major.
  void transform(const RigidTransform& t) {
    fixed(fem::column_major_of(t.rotation));
    fixed(t.translation);
    fixed(t.center);
  }
  void finish() {
    file_.flush();
    if (!file_) throw Error("write_checkpoint " + path_ + ": writing failed part way");
    file_.close();
    if (file_.fail()) throw Error("write_checkpoint " + path_ + ": closing failed");
  }

 private:
  std::string path_;
  std::ofstream file_;
};

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error("read_checkpoint " + path_ + ": the file cannot be opened");
    data_.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    if (file.bad()) throw Error("read_checkpoint " + path_ + ": reading failed");
  }
  [[noreturn]] void fail(const std::string& item, const std::string& what) const {
    throw Error("read_checkpoint " + path_ + ": " + item + ": " + what);
  }
  void bytes(void* out, size_t n, const std::string& item) {
    if (n > data_.size() - at_)
      fail(item, "the file ends after " + std::to_string(data_.size()) + " bytes, " + std::to_string(n) +
                     " more expected at byte " + std::to_string(at_) + " (truncated)");
    if (n > 0) std::memcpy(out, data_.data() + at_, n);
    at_ += n;
  }
  // One value as the writer stored it (host byte order).
  template <typename T>
  T value(const std::string& item) {
    T v{};
    bytes(&v, sizeof v, item);
    return v;
  }
  uint32_t u32(const std::string& item) { return value<uint32_t>(item); }
  uint64_t u64(const std::string& item) { return value<uint64_t>(item); }
  double f64(const std::string& item) { return value<double>(item); }
  bool flag(const std::string& item) {
    uint8_t b = 0;
    bytes(&b, 1, item);
    if (b > 1) fail(item, "expected 0 or 1, got " + std::to_string(b));
    return b == 1;
  }
  // A count of elements of `size` bytes each that the rest of the file can hold.
  size_t count(const std::string& item, size_t size) {
    const uint64_t n = u64(item + " count");
    if (n > (data_.size() - at_) / size)
      fail(item, std::to_string(n) + " entries of " + std::to_string(size) + " bytes, but only " +
                     std::to_string(data_.size() - at_) + " bytes remain (truncated)");
    return static_cast<size_t>(n);
  }
  std::string text(const std::string& item) {
    std::string s(count(item, 1), '\0');
    bytes(&s[0], s.size(), item);
    return s;
  }
  std::vector<double> values(const std::string& item) {
    std::vector<double> v(count(item, sizeof(double)));
    bytes(v.data(), v.size() * sizeof(double), item);
    return v;
  }
  template <size_t N>
  void fixed(std::array<double, N>& a, const std::string& item) {
    for (double& v : a) v = f64(item);
  }
  RigidTransform transform(const std::string& item) {
    RigidTransform t;
    std::array<double, 9> column_major;  // the file's order (see the writer)
    fixed(column_major, item + " rotation");
    t.rotation = fem::row_major_of(column_major);
    fixed(t.translation, item + " translation");
    fixed(t.center, item + " centre");
    return t;
  }
  // `v` holds `per` values per vertex (or none, where `may_be_empty`).
  void expect_size(const std::vector<double>& v, size_t expected, const std::string& item, bool may_be_empty) const {
    if (v.size() == expected || (may_be_empty && v.empty())) return;
    fail(item, std::to_string(v.size()) + " values, expected " + std::to_string(expected) +
                   (may_be_empty ? " or none" : "") + " (wrong size)");
  }
  // `v` as points (three values each).
  Points points(std::vector<double> v, const std::string& item) const {
    if (v.size() % 3 != 0) fail(item, std::to_string(v.size()) + " values, not three per point (wrong size)");
    return Points::from_xyz(std::move(v));
  }
  // The points of `item`, `expected` values (or none, where `may_be_empty`).
  Points points(const std::string& item, size_t expected, bool may_be_empty) {
    std::vector<double> v = values(item);
    expect_size(v, expected, item, may_be_empty);
    return points(std::move(v), item);
  }
  void finish() const {
    if (at_ != data_.size())
      fail("end", std::to_string(data_.size() - at_) + " bytes after the last item (wrong size)");
  }

 private:
  std::string path_;
  std::vector<char> data_;
  size_t at_ = 0;
};

}  // namespace

uint64_t mesh_fingerprint(const Mesh& mesh) {
  uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits
  auto add = [&hash](const void* data, size_t n) {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) hash = (hash ^ b[i]) * 1099511628211ull;
  };
  const uint32_t type = static_cast<uint32_t>(mesh.type);
  add(&type, sizeof type);
  add(mesh.positions.data(), mesh.positions.xyz().size() * sizeof(double));
  add(mesh.elements.data(), mesh.elements.size() * sizeof(int32_t));
  return hash;
}

void write_checkpoint(const std::string& path, const SimulationState& state) {
  Writer w(path);
  w.bytes(kMagic, sizeof kMagic);
  w.u32(kVersion);
  w.u32(kByteOrder);
  w.u64(state.vertex_count);
  w.u64(state.mesh_fingerprint);
  w.points(state.positions);
  w.points(state.velocities);
  w.f64(state.time);
  w.points(state.friction_anchors);
  w.u64(state.targets.size());
  for (const SimulationState::Target& t : state.targets) {
    w.text(t.set);
    w.u32(static_cast<uint32_t>(t.kind));
    w.transform(t.from);
    w.transform(t.to);
    w.flag(t.from_known);
    w.points(t.positions);
  }
  w.points(state.external_force);
  w.fixed(state.body_force);
  w.points(state.force_from);
  w.points(state.force_to);
  w.points(state.force_applied);
  w.finish();
}

SimulationState read_checkpoint(const std::string& path) {
  Reader r(path);
  char magic[sizeof kMagic];
  r.bytes(magic, sizeof magic, "header");
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("header", "not an snh checkpoint");
  const uint32_t version = r.u32("version");
  if (version != kVersion)
    r.fail("version",
           "version " + std::to_string(version) + ", this library reads version " + std::to_string(kVersion));
  if (r.u32("byte order") != kByteOrder) r.fail("byte order", "written on a machine of another byte order");
  SimulationState s;
  s.vertex_count = r.u64("vertex count");
  s.mesh_fingerprint = r.u64("mesh fingerprint");
  const size_t dofs = 3 * static_cast<size_t>(s.vertex_count);
  s.positions = r.points("positions", dofs, false);
  s.velocities = r.points("velocities", dofs, true);
  s.time = r.f64("time");
  std::vector<double> anchors = r.values("friction anchors");
  if (anchors.size() % (dofs > 0 ? dofs : 1) != 0)
    r.fail("friction anchors",
           std::to_string(anchors.size()) + " values, not a multiple of " + std::to_string(dofs) + " (wrong size)");
  s.friction_anchors = r.points(std::move(anchors), "friction anchors");
  s.targets.resize(r.count("targets", 1));
  for (size_t k = 0; k < s.targets.size(); ++k) {
    SimulationState::Target& t = s.targets[k];
    const std::string item = "target " + std::to_string(k);
    t.set = r.text(item + " set name");
    const uint32_t kind = r.u32(item + " kind");
    if (kind > static_cast<uint32_t>(TargetKind::positions))
      r.fail(item + " kind", "unknown kind " + std::to_string(kind));
    t.kind = static_cast<TargetKind>(kind);
    t.from = r.transform(item + " from");
    t.to = r.transform(item + " to");
    t.from_known = r.flag(item + " from_known");
    t.positions = r.points(r.values(item + " positions"), item + " positions");
  }
  s.external_force = r.points("external force", dofs, true);
  r.fixed(s.body_force, "body force");
  s.force_from = r.points("force from", dofs, false);
  s.force_to = r.points("force to", dofs, false);
  s.force_applied = r.points("force applied", dofs, true);
  r.finish();
  return s;
}

}  // namespace snh
