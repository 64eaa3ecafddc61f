#include "stages/kernel_paths.hpp"

namespace passim {

KernelPaths& kernel_paths() {
  static KernelPaths paths;
  return paths;
}

}  // namespace passim
