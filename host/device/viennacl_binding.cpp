#include "device/viennacl_binding.h"

#include <atomic>

#include "viennacl/ocl/backend.hpp"

namespace snh::device {

long bind_viennacl(const OpenClContext& cl) {
  static std::atomic<long> next_id{1000};
  const long id = next_id++;
  viennacl::ocl::setup_context(id, cl.context(), cl.device(), cl.queue());
  viennacl::ocl::switch_context(id);
  return id;
}

void use_viennacl(long id) { viennacl::ocl::switch_context(id); }

}  // namespace snh::device
