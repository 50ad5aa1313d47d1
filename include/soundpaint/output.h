// Writers for the command line's outputs (contract: README.md, "Command line"):
// the indicator CSV and the stats JSON. Files are written to a temporary name
// beside the target and renamed on commit, so a failure never leaves a
// half-written file.
#pragma once

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "soundpaint/simulation.h"

namespace sp {

// The exact CSV header of `soundpaint simulate --indicators` (contract).
inline constexpr const char* kIndicatorCsvHeader =
    "step,kind,source,x,y,z,nx,ny,nz,energy,bounces,penetrations,path_length,intensity,size,r,g,b,dx,dy,dz,"
    "diffractions";

// Streams indicators into a CSV file. Throws sp::Exception (ErrorCode::Io)
// on failure; the target file appears only after commit().
class IndicatorCsvWriter {
 public:
  explicit IndicatorCsvWriter(const std::filesystem::path& path);
  ~IndicatorCsvWriter();
  IndicatorCsvWriter(const IndicatorCsvWriter&) = delete;
  IndicatorCsvWriter& operator=(const IndicatorCsvWriter&) = delete;

  void write(std::span<const Indicator> indicators);
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Wall-clock and GPU timing of the steps of one run, milliseconds.
struct StepTimings {
  std::vector<double> wall_ms;  // one per step
  std::vector<double> gpu_ms;   // one per step; empty for the CPU backend
};

double median(std::vector<double> values);
double percentile(std::vector<double> values, double p);  // p in [0, 100], nearest rank

// The stats JSON object (contract: README.md, "Command line") as text.
std::string stats_json(const World& world, const SimulationStats& stats, const char* backend_name,
                       const std::string& device, const StepTimings& timings);

// Writes `text` to `path` atomically (temporary file + rename).
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace sp
