#include "device/kernel_source.h"

#include <set>
#include <sstream>

#include "snh/error.h"

namespace snh::device {

// Generated: the embedded files (path relative to kernels/, contents).
struct EmbeddedKernelFile {
  const char* path;
  const char* text;
};
extern const EmbeddedKernelFile kEmbeddedKernelFiles[];
extern const int kEmbeddedKernelFileCount;

namespace {

const char* find_file(const std::string& path) {
  for (int i = 0; i < kEmbeddedKernelFileCount; ++i)
    if (path == kEmbeddedKernelFiles[i].path) return kEmbeddedKernelFiles[i].text;
  return nullptr;
}

void append_resolved(const std::string& path, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(path).second) return;  // include guards would skip it anyway
  const char* text = find_file(path);
  if (!text) throw Error("kernel source: no embedded file kernels/" + path);
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
      const auto open = line.find('"', first);
      const auto close = open == std::string::npos ? open : line.find('"', open + 1);
      if (close != std::string::npos) {
        append_resolved(line.substr(open + 1, close - open - 1), seen, out);
        continue;
      }
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string kernel_program_source(const std::string& name) {
  std::set<std::string> seen;
  std::string out;
  append_resolved(name, seen, out);
  return out;
}

}  // namespace snh::device
