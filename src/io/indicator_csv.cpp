#include <charconv>
#include <string>

#include "io/atomic_file.h"
#include "io/output.h"
#include "sp_types.h"

namespace sp {
namespace {

// Shortest text that reads back as the same float: CSVs of two runs compare
// equal exactly when the values do.
void append_float(std::string& out, float value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ec == std::errc{} ? end : buffer);
  out.push_back(',');
}

void append_uint(std::string& out, std::uint64_t value) {
  char buffer[24];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ec == std::errc{} ? end : buffer);
  out.push_back(',');
}

// A vector as three columns.
void append_vec3(std::string& out, const Vec3& v) {
  append_float(out, v.x);
  append_float(out, v.y);
  append_float(out, v.z);
}

}  // namespace

struct IndicatorCsvWriter::Impl {
  explicit Impl(const std::filesystem::path& path) : file(path) {}
  AtomicFile file;
  std::string buffer;
};

IndicatorCsvWriter::IndicatorCsvWriter() = default;

Result<std::unique_ptr<IndicatorCsvWriter>> IndicatorCsvWriter::open(const std::filesystem::path& path) {
  return capture_errors(
      [&] {
        std::unique_ptr<IndicatorCsvWriter> writer(new IndicatorCsvWriter());
        writer->impl_ = std::make_unique<Impl>(path);
        writer->impl_->file.write(std::string(kIndicatorCsvHeader) + "\n");
        return writer;
      },
      ErrorCode::Io);
}

IndicatorCsvWriter::~IndicatorCsvWriter() = default;

Result<bool> IndicatorCsvWriter::write(std::span<const Indicator> indicators) {
  return capture_errors(
      [&] {
        std::string& out = impl_->buffer;
        out.clear();
        for (const Indicator& ind : indicators) {
          append_uint(out, ind.step);
          out += ind.kind == SP_INDICATOR_HIT ? "hit," : "exit,";
          append_uint(out, ind.source_id);
          append_vec3(out, ind.position);
          append_vec3(out, ind.normal);
          append_float(out, ind.energy);
          append_uint(out, ind.bounces);
          append_uint(out, ind.penetrations);
          append_float(out, ind.path_length);
          append_float(out, ind.intensity);
          append_float(out, ind.size);
          append_vec3(out, ind.color);
          append_vec3(out, ind.dir);
          append_uint(out, ind.diffractions);
          append_float(out, ind.heard_energy);
          append_vec3(out, ind.arrival);
          append_float(out, ind.toward);
          out.back() = '\n';
        }
        impl_->file.write(out);
        return true;
      },
      ErrorCode::Io);
}

Result<bool> IndicatorCsvWriter::commit() {
  return capture_errors(
      [&] {
        impl_->file.commit();
        return true;
      },
      ErrorCode::Io);
}

Result<bool> write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  return capture_errors(
      [&] {
        AtomicFile file(path);
        file.write(text);
        file.commit();
        return true;
      },
      ErrorCode::Io);
}

}  // namespace sp
