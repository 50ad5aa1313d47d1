// Writers for the command line's outputs (contract: README.md, "Command
// line"): the indicator CSV and the stats JSON. Files are written to a
// temporary name beside the target and renamed on commit, so a failure
// never leaves a half-written file. Not installed: CLI and bench helpers,
// not the library's API.
#pragma once

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "soundpaint/result.h"
#include "soundpaint/simulation.h"

namespace sp {

// The exact CSV header of `soundpaint simulate --indicators`: the contract's
// columns, then ours (readers go by name): what reaches the player
// (docs/model.md#cues-for-the-player): the energy heard at the listener, the
// direction the sound arrives from, and how nearly it points at its source.
inline constexpr const char* kIndicatorCsvHeader =
    "step,kind,source,x,y,z,nx,ny,nz,energy,bounces,penetrations,path_length,intensity,size,r,g,b,dx,dy,dz,"
    "diffractions,heard,ax,ay,az,toward";

// Streams indicators into a CSV file; the target file appears only after
// commit(). Errors are ErrorCode::Io naming the path; after one, the writer
// is unusable and the target untouched (the temporary file is removed).
class IndicatorCsvWriter {
 public:
  // Opens a temporary file beside `path` and writes the header.
  static Result<std::unique_ptr<IndicatorCsvWriter>> open(const std::filesystem::path& path);
  ~IndicatorCsvWriter();
  IndicatorCsvWriter(const IndicatorCsvWriter&) = delete;
  IndicatorCsvWriter& operator=(const IndicatorCsvWriter&) = delete;

  Result<bool> write(std::span<const Indicator> indicators);
  Result<bool> commit();

 private:
  IndicatorCsvWriter();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Wall-clock and GPU timing of the steps of one run, milliseconds.
struct StepTimings {
  std::vector<double> wall_ms;  // one per step
  std::vector<double> gpu_ms;   // one per step; empty for the CPU backend
};

// Cannot fail: 0 for an empty list.
double median(std::vector<double> values);
double percentile(std::vector<double> values, double p);  // p in [0, 100] (clamped), nearest rank

// The stats JSON object (contract: README.md, "Command line") as text.
// Cannot fail (but for std::bad_alloc): every count is a number; layers
// without counters are left out.

std::string stats_json(const World& world, const SimulationStats& stats, const char* backend_name,
                       const std::string& device, const StepTimings& timings);

// Writes `text` to `path` atomically (temporary file + rename).
// ErrorCode::Io naming the path when it cannot.
Result<bool> write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace sp
