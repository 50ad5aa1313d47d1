// The simulation backends the physics tests run on: the CPU with its own
// traversal, the GPU, and, in a build with Embree (-DSOUNDPAINT_EMBREE=ON),
// the CPU casting through Embree (cpu_traversal "embree"), which must obey
// the same hand-derived physics.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "soundpaint/config.h"
#include "soundpaint/simulation.h"

namespace sp::test {

struct BackendCase {
  Backend backend = Backend::Cpu;
  CpuTraversal traversal = CpuTraversal::Soundpaint;
};

// gtest's description of a failing case's parameter.
inline void PrintTo(const BackendCase& c, std::ostream* os) {
  *os << (c.backend == Backend::Gpu ? "GPU" : "CPU") << ", "
      << (c.traversal == CpuTraversal::Embree ? "Embree" : "soundpaint") << " traversal";
}

inline std::vector<BackendCase> backend_cases() {
  std::vector<BackendCase> cases = {{Backend::Cpu, CpuTraversal::Soundpaint}, {Backend::Gpu, CpuTraversal::Soundpaint}};
  if (embree_available()) cases.push_back({Backend::Cpu, CpuTraversal::Embree});
  return cases;
}

inline std::string backend_case_name(const ::testing::TestParamInfo<BackendCase>& info) {
  if (info.param.backend == Backend::Gpu) return "Gpu";
  return info.param.traversal == CpuTraversal::Embree ? "CpuEmbree" : "Cpu";
}

// `config` with the case's CPU traversal.
inline Config with_traversal(Config config, BackendCase c) {
  config.cpu_traversal = c.traversal;
  return config;
}

}  // namespace sp::test
