#include "device/kernel_config.h"

#include <algorithm>
#include <mutex>
#include <sstream>

#include "snh/error.h"

namespace snh::device {

namespace {

// A switch: its name and how it reads and writes its field. `get` gives
// the value to write, or nothing where the field leaves it out; `set`
// stores a parsed value, or returns false where the value is out of range.
struct Switch {
  const char* name;
  std::optional<int> (*get)(const KernelConfig&);
  bool (*set)(KernelConfig&, int);
};

constexpr int kModels = static_cast<int>(MaterialModel::neohookean) + 1;

std::optional<int> flag(bool on) { return on ? std::optional<int>(1) : std::nullopt; }
std::optional<int> count(int n) { return n > 0 ? std::optional<int>(n) : std::nullopt; }
std::optional<int> boolean(const std::optional<bool>& b) { return b ? std::optional<int>(*b ? 1 : 0) : std::nullopt; }
std::optional<int> model_id(const std::optional<MaterialModel>& m) {
  return m ? std::optional<int>(static_cast<int>(*m)) : std::nullopt;
}
bool set_flag(bool& field, int v) {
  field = v == 1;
  return v == 0 || v == 1;
}
bool set_count(int& field, int v) {
  field = v;
  return v >= 0;
}
bool set_boolean(std::optional<bool>& field, int v) {
  field = v == 1;
  return v == 0 || v == 1;
}
bool set_model(std::optional<MaterialModel>& field, int v) {
  field = static_cast<MaterialModel>(v);
  return v >= 0 && v < kModels;
}

// The order the switches are written in: element, material, layout,
// per-vertex terms, then the switches of single programs. The kernel
// specialization that results report is this order's first part.
const Switch kSwitches[] = {
    {"SNH_HEX8",
     [](const KernelConfig& c) {
       return c.element ? std::optional<int>(*c.element == ElementType::hex8 ? 1 : 0) : std::nullopt;
     },
     [](KernelConfig& c, int v) {
       c.element = v == 1 ? ElementType::hex8 : ElementType::tet4;
       return v == 0 || v == 1;
     }},
    {"SNH_GENERAL_KERNEL", [](const KernelConfig& c) { return flag(c.general_material); },
     [](KernelConfig& c, int v) { return set_flag(c.general_material, v); }},
    {"SNH_MODEL", [](const KernelConfig& c) { return model_id(c.model); },
     [](KernelConfig& c, int v) { return set_model(c.model, v); }},
    {"SNH_BARRIER", [](const KernelConfig& c) { return boolean(c.barrier); },
     [](KernelConfig& c, int v) { return set_boolean(c.barrier, v); }},
    {"SNH_NONLINEAR", [](const KernelConfig& c) { return boolean(c.nonlinear); },
     [](KernelConfig& c, int v) { return set_boolean(c.nonlinear, v); }},
    {"SNH_LAMBDA_MODEL", [](const KernelConfig& c) { return model_id(c.lambda_model); },
     [](KernelConfig& c, int v) { return set_model(c.lambda_model, v); }},
    {"SNH_REGIONS", [](const KernelConfig& c) { return flag(c.regions); },
     [](KernelConfig& c, int v) { return set_flag(c.regions, v); }},
    {"SNH_UNIFORM_REST", [](const KernelConfig& c) { return boolean(c.uniform_rest); },
     [](KernelConfig& c, int v) { return set_boolean(c.uniform_rest, v); }},
    {"SNH_POINT_MAJOR", [](const KernelConfig& c) { return flag(c.point_major); },
     [](KernelConfig& c, int v) { return set_flag(c.point_major, v); }},
    {"SNH_CACHE_TILE", [](const KernelConfig& c) { return count(c.cache_tile); },
     [](KernelConfig& c, int v) { return set_count(c.cache_tile, v); }},
    {"SNH_STENCIL_TILE", [](const KernelConfig& c) { return count(c.stencil_tile); },
     [](KernelConfig& c, int v) { return set_count(c.stencil_tile, v); }},
    {"SNH_INERTIA", [](const KernelConfig& c) { return flag(c.inertia); },
     [](KernelConfig& c, int v) { return set_flag(c.inertia, v); }},
    {"SNH_OBSTACLES", [](const KernelConfig& c) { return count(c.obstacles); },
     [](KernelConfig& c, int v) { return set_count(c.obstacles, v); }},
    {"SNH_SELF_CONTACT", [](const KernelConfig& c) { return flag(c.self_contact); },
     [](KernelConfig& c, int v) { return set_flag(c.self_contact, v); }},
    {"SNH_SELF_BARRIER", [](const KernelConfig& c) { return flag(c.self_barrier); },
     [](KernelConfig& c, int v) { return set_flag(c.self_barrier, v); }},
    {"SNH_FRICTION", [](const KernelConfig& c) { return flag(c.friction); },
     [](KernelConfig& c, int v) { return set_flag(c.friction, v); }},
    {"SNH_SURFACE_CONTACT", [](const KernelConfig& c) { return flag(c.surface_contact); },
     [](KernelConfig& c, int v) { return set_flag(c.surface_contact, v); }},
    {"SNH_LANES", [](const KernelConfig& c) { return count(c.lanes); },
     [](KernelConfig& c, int v) { return set_count(c.lanes, v); }},
    {"SNH_MIXED", [](const KernelConfig& c) { return flag(c.mixed); },
     [](KernelConfig& c, int v) { return set_flag(c.mixed, v); }},
    {"SNH_MATRIX_FLOAT", [](const KernelConfig& c) { return flag(c.matrix_float); },
     [](KernelConfig& c, int v) { return set_flag(c.matrix_float, v); }},
    {"SNH_FLOAT", [](const KernelConfig& c) { return flag(c.float_cycle); },
     [](KernelConfig& c, int v) { return set_flag(c.float_cycle, v); }},
    {"SNH_STENCIL_WIDTH", [](const KernelConfig& c) { return count(c.stencil_width); },
     [](KernelConfig& c, int v) { return set_count(c.stencil_width, v); }},
    {"SNH_STENCIL_LOWER", [](const KernelConfig& c) { return count(c.stencil_lower); },
     [](KernelConfig& c, int v) { return set_count(c.stencil_lower, v); }},
    {"SNH_FMA_CHAINS", [](const KernelConfig& c) { return count(c.fma_chains); },
     [](KernelConfig& c, int v) { return set_count(c.fma_chains, v); }},
    {"SNH_CG_CHECK", [](const KernelConfig& c) { return count(c.cg_check); },
     [](KernelConfig& c, int v) { return set_count(c.cg_check, v); }},
    {"SNH_CG_SPAN", [](const KernelConfig& c) { return count(c.cg_span); },
     [](KernelConfig& c, int v) { return set_count(c.cg_span, v); }},
    {"SNH_GPU", [](const KernelConfig& c) { return flag(c.gpu); },
     [](KernelConfig& c, int v) { return set_flag(c.gpu, v); }},
};

constexpr const char* kPrecisionSwitch = "SNH_DOUBLE";

void append(std::string& out, const char* name, int value) {
  if (!out.empty()) out += ' ';
  out += "-D";
  out += name;
  out += '=';
  out += std::to_string(value);
}

std::string precision_define(const KernelConfig& c) {
  if (!c.precision) throw Error("kernel build: the configuration has no precision (SNH_DOUBLE)");
  return std::string("-D") + kPrecisionSwitch + '=' + (*c.precision == Precision::double_ ? "1" : "0");
}

std::mutex& recorders_mutex() {
  static std::mutex m;
  return m;
}
std::vector<std::vector<BuiltProgram>*>& recorders() {
  static std::vector<std::vector<BuiltProgram>*> r;
  return r;
}

}  // namespace

std::string KernelConfig::defines() const {
  std::string out;
  for (const Switch& s : kSwitches)
    if (const std::optional<int> v = s.get(*this)) append(out, s.name, *v);
  return out;
}

std::string KernelConfig::report() const {
  const std::string d = defines();
  return d + (d.empty() ? "" : " ") + precision_define(*this);
}

std::string KernelConfig::build_options(bool on_gpu) const {
  KernelConfig c = *this;
  c.gpu = c.gpu || on_gpu;
  // -DSNH_DOUBLE first, as the kernels' portability header reads it first.
  const std::string d = c.defines();
  return "-cl-std=CL1.2 " + precision_define(c) + (d.empty() ? "" : " " + d);
}

KernelConfig KernelConfig::parse(const std::string& defines) {
  KernelConfig c;
  std::istringstream in(defines);
  std::string token;
  while (in >> token) {
    const size_t eq = token.find('=');
    if (token.rfind("-D", 0) != 0 || eq == std::string::npos)
      throw Error("kernel build: '" + token + "' is not a -DNAME=value switch");
    const std::string name = token.substr(2, eq - 2), text = token.substr(eq + 1);
    int value = 0;
    size_t used = 0;
    try {
      value = std::stoi(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size())
      throw Error("kernel build: switch " + name + " has the value '" + text + "', not a whole number");
    if (name == kPrecisionSwitch) {
      if (value != 0 && value != 1) throw Error("kernel build: switch SNH_DOUBLE is 0 or 1, not " + text);
      c.precision = value == 1 ? Precision::double_ : Precision::single;
      continue;
    }
    const Switch* s =
        std::find_if(std::begin(kSwitches), std::end(kSwitches), [&](const Switch& k) { return name == k.name; });
    if (s == std::end(kSwitches)) throw Error("kernel build: unknown switch " + name);
    if (!s->set(c, value)) throw Error("kernel build: switch " + name + " cannot be " + text);
  }
  return c;
}

KernelConfig KernelConfig::with_lanes(int n) const {
  KernelConfig c = *this;
  c.lanes = n;
  return c;
}

KernelConfig KernelConfig::with_mixed() const {
  KernelConfig c = *this;
  c.mixed = true;
  return c;
}

KernelConfig KernelConfig::with_matrix_float() const {
  KernelConfig c = *this;
  c.matrix_float = true;
  return c;
}

KernelConfig KernelConfig::with_float_cycle() const {
  KernelConfig c = *this;
  c.float_cycle = true;
  return c;
}

KernelConfig KernelConfig::with_stencil(int width, int lower) const {
  KernelConfig c = *this;
  c.stencil_width = width;
  c.stencil_lower = lower;
  return c;
}

KernelConfig KernelConfig::elastic() const {
  KernelConfig c = *this;
  c.inertia = false;
  c.obstacles = 0;
  c.self_contact = false;
  c.self_barrier = false;
  c.friction = false;
  c.surface_contact = false;
  return c;
}

KernelConfig KernelConfig::with_surface_contact() const {
  KernelConfig c = *this;
  c.surface_contact = true;
  return c;
}

std::vector<std::string> kernel_switch_names() {
  std::vector<std::string> names;
  for (const Switch& s : kSwitches) names.emplace_back(s.name);
  names.emplace_back(kPrecisionSwitch);
  return names;
}

ProgramRecorder::ProgramRecorder() {
  std::lock_guard<std::mutex> lock(recorders_mutex());
  recorders().push_back(&programs_);
}

ProgramRecorder::~ProgramRecorder() {
  std::lock_guard<std::mutex> lock(recorders_mutex());
  auto& r = recorders();
  r.erase(std::remove(r.begin(), r.end(), &programs_), r.end());
}

void ProgramRecorder::record(const std::string& file, const KernelConfig& config) {
  std::lock_guard<std::mutex> lock(recorders_mutex());
  for (std::vector<BuiltProgram>* r : recorders()) r->push_back(BuiltProgram{file, config});
}

}  // namespace snh::device
